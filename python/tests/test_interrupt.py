"""Ctrl-C stops a long call at its next step and raises KeyboardInterrupt there (it was deferred to
the end of the call: a 20 000-variant study interrupted at 2 s stopped at 68 s).

The study runs in a child Python, which is sent SIGINT as soon as its progress shows a variant
done; the test reads how far the progress got: fewer than all variants means the call
stopped, not that it finished and Python raised afterwards. No timing assertion: the 120 s
limit only guards against a hang.
"""

import os
import re
import signal
import subprocess
import sys
import time

from conftest import FISHFIN

VARIANTS = 20000
SCRIPT = f"""
import sys
import emnet
try:
    emnet.study(sys.argv[1], vary=["beam.bending_stiffness=uniform(95%,105%)"], samples={VARIANTS}, threads=1,
                progress=True)
    print("finished")
except KeyboardInterrupt:
    print("interrupted")
"""


def _read_until(stream, pattern, seconds):
    """What `stream` gives until it matches `pattern` or `seconds` pass."""
    seen = b""
    until = time.monotonic() + seconds
    os.set_blocking(stream.fileno(), False)
    while not pattern.search(seen) and time.monotonic() < until:
        try:
            chunk = os.read(stream.fileno(), 4096)
        except BlockingIOError:
            time.sleep(0.02)
            continue
        if not chunk:
            break
        seen += chunk
    return seen


def test_ctrl_c_stops_a_long_study_inside_the_call():
    child = subprocess.Popen([sys.executable, "-c", SCRIPT, FISHFIN], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE)
    try:
        # A count above 0: the call is running (the bar's 0/N is drawn before it starts).
        before = _read_until(child.stderr, re.compile(rb"[1-9]\d*/%d" % VARIANTS), 120)
        assert re.search(rb"[1-9]\d*/%d" % VARIANTS, before), before
        child.send_signal(signal.SIGINT)
        os.set_blocking(child.stderr.fileno(), True)
        out, err = child.communicate(timeout=120)
    finally:
        child.kill()
        child.wait()
    assert out.decode().strip() == "interrupted", (out, before + err)
    counts = [int(done) for done in re.findall(rb"(\d+)/%d" % VARIANTS, before + err)]
    assert counts and max(counts) < VARIANTS, counts
