"""Notebooks: the tutorial (examples/tutorial.ipynb) runs top to bottom in a fresh Jupyter kernel
and prints what emnet computes here; interrupting a kernel (a notebook's stop button) stops a
long study inside the call.

Kernels come from ipykernel's own "python3" spec, which runs this Python (`-m
ipykernel_launcher`) whatever kernelspecs are installed, so the tests run offline and from a
fresh clone. A kernel inherits this process's environment: PYTHONPATH finds the emnet under test.
Skipped only when nbclient, nbformat, jupyter_client or ipykernel is not importable.
"""

import base64
import os
import pathlib
import re
import time

import pytest

import emnet
from conftest import FISHFIN, ROOT

REASON = "needs {} (Debian python3-nbclient, python3-nbformat, python3-ipykernel)"
nbformat = pytest.importorskip("nbformat", reason=REASON.format("nbformat"))
nbclient = pytest.importorskip("nbclient", reason=REASON.format("nbclient"))
pytest.importorskip("ipykernel", reason=REASON.format("ipykernel"))
pytest.importorskip("jupyter_client", reason=REASON.format("jupyter_client"))

NOTEBOOK = ROOT / "examples" / "tutorial.ipynb"
HANG = 120  # seconds: only a guard against a hang, far above anything here


@pytest.fixture(autouse=True)
def _own_jupyter_folders(tmp_path, monkeypatch):
    """Connection files and IPython's profile in the test's folder, not the user's home."""
    monkeypatch.setenv("JUPYTER_RUNTIME_DIR", str(tmp_path / "jupyter-runtime"))
    monkeypatch.setenv("IPYTHONDIR", str(tmp_path / "ipython"))


def _kernel_manager(manager_class):
    """A kernel manager of ipykernel's own python3 spec (no kernel directories searched)."""
    from jupyter_client.kernelspec import KernelSpecManager

    return manager_class(kernel_name="python3",
                         kernel_spec_manager=KernelSpecManager(kernel_dirs=[]))


def _kernel_environment():
    environment = dict(os.environ)
    # The notebook finds the repository itself, from the folder it runs in, as in a fresh clone.
    environment.pop("EMNET_ROOT", None)
    # ipykernel forwards output written to its file descriptors (the C++ progress) except under
    # pytest, which it recognises by this variable: the kernel is not under pytest.
    environment.pop("PYTEST_CURRENT_TEST", None)
    environment["MPLBACKEND"] = "agg"  # no display; the notebook asks for inline itself
    environment["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # quiets the kernel's debugger warning
    return environment


def _outputs(notebook):
    """{cell id: (printed text, [mime bundles of the displayed data])}."""
    found = {}
    for cell in notebook.cells:
        if cell.cell_type != "code":
            continue
        text = "".join(out.get("text", "") for out in cell.outputs if out.output_type == "stream")
        data = [out.data for out in cell.outputs
                if out.output_type in ("display_data", "execute_result")]
        found[cell.id] = (text, data)
    return found


def _number(pattern, text):
    match = re.search(pattern, text)
    assert match, (pattern, text)
    return float(match.group(1))


def test_tutorial_notebook_runs_and_shows_what_emnet_computes():
    """Every cell runs without error (nbclient raises at the first failing cell) in the
    notebook's own folder with EMNET_ROOT unset, as a user's fresh clone runs it. What it prints
    is what emnet computes in this process: the first mode, the resonances of the Bode plot and
    the study's range of f1, each printed as repr(float) and compared exactly; and the kernel
    used the emnet under test. Both figures are drawn inline (MPLBACKEND is agg in the kernel,
    so the notebook's own %matplotlib inline does it)."""
    from jupyter_client.manager import AsyncKernelManager

    notebook = nbformat.read(NOTEBOOK, as_version=4)
    assert all(cell.get("outputs", []) == [] for cell in notebook.cells), \
        "commit the notebook with its outputs cleared"
    client = nbclient.NotebookClient(notebook, km=_kernel_manager(AsyncKernelManager),
                                     timeout=HANG, startup_timeout=HANG,
                                     resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    client.execute(env=_kernel_environment())  # raises CellExecutionError at any cell's error
    out = _outputs(notebook)

    setup = out["setup"][0]
    assert re.search(r"repository: (.*)", setup).group(1) == str(ROOT.resolve())
    assert re.search(r"emnet module: (.*)", setup).group(1) == \
        str(pathlib.Path(emnet.__file__).parent)

    finger = emnet.Scene(ROOT / "netlists" / "gripper-finger.toml")
    # The notebook prints repr(float): it reads back exactly, so equality is the check.
    expected_f1 = emnet.modes(finger, count=4).modes["frequency_hz"][0]
    assert _number(r"first mode: (\S+) Hz", out["modes"][0]) == expected_f1
    table = out["modes"][1][0]
    assert "text/html" in table and "natural_frequency_hz" in table["text/html"]

    printed = re.search(r"resonances in the band \[Hz\]: (.*)", out["bode"][0]).group(1)
    assert [float(f) for f in printed.split(",")] == list(emnet.ac(finger).resonances_hz)

    study = emnet.study(finger, vary=["section[0].bending_stiffness=normal(100%,10%)",
                                      "dea.A.dielectric_thickness+dea.A.force_thickness="
                                      "uniform(90%,110%)"],
                        samples=200, seed=1, analyses=["modes", "static"], modes=2)
    assert "200 variants, 0 failed" in out["study"][0]
    assert _number(r"f1 from (\S+) to", out["study"][0]) == study["f1_hz"].min()
    assert _number(r"to (\S+) Hz", out["study"][0]) == study["f1_hz"].max()

    # Both figures are PNG images of real plots: 40 to 50 kB; empty axes of the same sizes
    # are 5 to 8 kB.
    for cell in ("bode", "plot"):
        images = [base64.b64decode(data["image/png"]) for data in out[cell][1]
                  if "image/png" in data]
        assert len(images) == 1, cell
        assert images[0].startswith(b"\x89PNG") and len(images[0]) > 20000, (cell, len(images[0]))


VARIANTS = 20000
SETUP = f"""
import time
import emnet
fin = emnet.Scene({FISHFIN!r})
vary = ["beam.bending_stiffness=uniform(95%,105%)"]
cost = emnet.study(fin, vary=vary, samples=100, threads=1).attrs["cost"]
"""
LONG_STUDY = f"""
started = time.perf_counter()
emnet.study(fin, vary=vary, samples={VARIANTS}, threads=1, progress=True)
"""
AFTER = f"print(time.perf_counter() - started, cost['per_variant_seconds'] * {VARIANTS})"


def _run(kernel, code, on_output=None):
    """Executes `code` in `kernel`; calls on_output(text) with each stream output as it comes.
    Returns the execute reply's content and everything printed."""
    msg_id = kernel.execute(code)
    printed = ""
    until = time.monotonic() + HANG
    while True:
        message = kernel.get_iopub_msg(timeout=max(0.1, until - time.monotonic()))
        if message["parent_header"].get("msg_id") != msg_id:
            continue
        content = message["content"]
        if message["msg_type"] == "stream":
            printed += content["text"]
            if on_output is not None:
                on_output(printed)
        elif message["msg_type"] == "status" and content["execution_state"] == "idle":
            break
    reply = kernel.get_shell_msg(timeout=HANG)
    assert reply["parent_header"]["msg_id"] == msg_id
    return reply["content"], printed


def test_interrupting_a_kernel_stops_a_long_study_inside_the_call():
    """The stop button of a notebook is km.interrupt_kernel(), a SIGINT to the kernel. It is sent
    once the study's progress shows a variant done (the bar on the kernel's standard error, which
    ipykernel forwards to the notebook; its first line, 0 done, is drawn before the call). The call must end
    with KeyboardInterrupt, and the kernel answer the next cell. That the call stopped, rather
    than finished and raised afterwards, shows twice: the progress count stays below the
    variants, and the time from the study's start to the next cell is under half of what the
    whole study takes at the per-variant cost the kernel measured first (the solves alone: 20 000
    variants take about 35 s here, and the interrupt ends the call within a second)."""
    from jupyter_client.manager import KernelManager

    manager = _kernel_manager(KernelManager)
    # capture_fd_output (the default since ipykernel 6) forwards the C++ progress to the client.
    manager.start_kernel(env=_kernel_environment(),
                         extra_arguments=["--IPKernelApp.capture_fd_output=True"])
    kernel = manager.client()
    try:
        kernel.start_channels()
        kernel.wait_for_ready(timeout=HANG)
        reply, _ = _run(kernel, SETUP)
        assert reply["status"] == "ok", reply

        sent = []

        def interrupt_at_first_progress(printed):
            # A count above 0: the call is running (the bar's 0/N is drawn before it starts).
            if not sent and any(int(done) > 0 for done in
                                re.findall(r"(\d+)/%d" % VARIANTS, printed)):
                sent.append(time.monotonic())
                manager.interrupt_kernel()

        reply, printed = _run(kernel, LONG_STUDY, interrupt_at_first_progress)
        assert sent, printed
        assert reply["status"] == "error" and reply["ename"] == "KeyboardInterrupt", reply
        stopped_after = time.monotonic() - sent[0]

        asked = time.monotonic()
        answer, elapsed = _run(kernel, AFTER)
        if answer["status"] == "aborted":
            # A request that reaches ipykernel in the moment after an error is aborted, as "run
            # all" stops at a failing cell; this one is asked again, once.
            answer, elapsed = _run(kernel, AFTER)
        answered_after = time.monotonic() - asked
        assert answer["status"] == "ok", answer
    finally:
        kernel.stop_channels()
        manager.shutdown_kernel(now=True)

    counts = [int(done) for done in re.findall(r"(\d+)/%d" % VARIANTS, printed)]
    assert counts and max(counts) < VARIANTS, counts
    since_start, whole_study = map(float, elapsed.split())
    assert since_start < whole_study / 2, (since_start, whole_study)
    print(f"interrupted at {max(counts)}/{VARIANTS} variants; KeyboardInterrupt {stopped_after:.2f}"
          f" s after the interrupt; next cell answered in {answered_after:.2f} s; the study ran"
          f" {since_start:.2f} s of the {whole_study:.1f} s it would take")
