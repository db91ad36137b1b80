"""Memory stays flat over many calls: a script or a notebook that calls emnet in a loop (a
hand-written study, an optimiser) must not grow, whether the calls succeed or fail.

The measure is the process's resident set (/proc/self/statm), which counts what the C++ library
allocates as well as Python objects, after a warm-up that fills the allocators' pools and the
caches. The bound, 5 MB, is far above the noise (the growth measured here is under 0.1 MB) and
far below a leak of anything a call makes: kept alive, a static Result of the fin takes about
6 kB, a modes Result 9 kB, an ac Result 4 kB, a scene copy 13 kB (each measured by keeping them
in a list). Over 10 000 calls 5 MB is 500 bytes a call.
"""

import gc
import os
import time

import pytest

import emnet

BOUND = 5e6  # bytes
PAGE = os.sysconf("SC_PAGE_SIZE")


def _resident_bytes():
    with open("/proc/self/statm", encoding="ascii") as statm:
        return int(statm.read().split()[1]) * PAGE


def _growth(call, warm_up, calls, what="calls"):
    """The resident set's growth [bytes] over `calls` calls after `warm_up` calls (printed with
    the resident set before and after and the time per call)."""
    for _ in range(warm_up):
        call()
    gc.collect()
    before = _resident_bytes()
    started = time.perf_counter()
    for _ in range(calls):
        call()
    seconds = (time.perf_counter() - started) / calls
    gc.collect()
    after = _resident_bytes()
    print(f"\n{calls} {what}: resident {before / 1e6:.2f} MB -> {after / 1e6:.2f} MB "
          f"({(after - before) / 1e3:+.0f} kB), {seconds * 1e3:.3f} ms each")
    return after - before


@pytest.fixture(autouse=True, scope="module")
def _linux_only():
    if not os.path.exists("/proc/self/statm"):
        pytest.skip("needs /proc/self/statm (Linux)")


def test_static_calls_keep_memory_flat(fishfin):
    # 10 000 static solves of the fin (about 0.2 ms each; 2 s): the whole path from the scene to
    # the network, its solve and the Result with its numpy arrays.
    assert _growth(lambda: emnet.static(fishfin), 1000, 10000) < BOUND


def test_failing_calls_keep_memory_flat(fishfin):
    # 10 000 calls that raise emnet.InputError (a probe text that names no place): the error
    # path, where an exception's references are easy to leak.
    def failing():
        try:
            emnet.static(fishfin, probes=["deflection@nowhere"])
        except emnet.InputError:
            return
        raise AssertionError("expected an InputError")

    assert _growth(failing, 1000, 10000) < BOUND


def test_scene_copies_modes_and_ac_keep_memory_flat(fishfin):
    # 1000 rounds (3000 calls, about 6 s) of what a hand-written study does per variant: a
    # changed copy of the scene, its lowest mode and a two-point frequency response (complex
    # phasors). 5 MB is 5 kB a round, less than any one of the three results or the copy.
    def one_variant():
        scene = fishfin.with_values({"beam.bending_stiffness": 2.2e-3})
        emnet.modes(scene, count=1, error_estimate=False)
        emnet.ac(scene, points=2)

    assert _growth(one_variant, 100, 1000, "rounds") < BOUND
