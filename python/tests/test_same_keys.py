"""The same keys in both front-ends: every analysis's Python result against `emnet COMMAND --json`.

Both print one JSON per result, written in the library's report layer (include/emnet/report/);
Python converts it (an array of records becomes a dict of columns, one per key). So the key
paths of the two must be equal, recursively: an array's elements share their parent's path.
The only keys that differ are named here, with why.
"""

import pytest

import emnet
from conftest import CANTILEVER, FISHFIN, cli_json

# What one front-end has and the other cannot: Python's complex AC responses (JSON has no
# complex numbers), the deck's text in Python where the command writes it to a file and names
# that file.
PYTHON_ONLY = {"ac": {"/phasors"}, "netlist": {"/text"}}
COMMAND_ONLY = {"netlist": {"/deck"}}


def key_paths(value, prefix=""):
    """Every key's path ("/modes/frequency_hz"); arrays and lists pass through to their items."""
    paths = set()
    if isinstance(value, dict):
        for key, item in value.items():
            path = f"{prefix}/{key}"
            paths.add(path)
            paths |= key_paths(item, path)
    elif isinstance(value, (list, tuple)):
        for item in value:
            paths |= key_paths(item, prefix)
    return paths


def ideal(scene):
    return scene.with_overrides({"drive.electrical_dynamics": False})


CASES = {
    "static": (("static", CANTILEVER), lambda s: emnet.static(s["cantilever"])),
    "static with probes": (("static", FISHFIN, "--probe", "tip", "--probe", "P4"),
                           lambda s: emnet.static(s["fishfin"], probes=["tip", "P4"])),
    "modes": (("modes", FISHFIN, "--count", "3", "--shapes", "--probe", "P4"),
              lambda s: emnet.modes(s["fishfin"], count=3, shapes=True, probes=["P4"])),
    "ac": (("ac", CANTILEVER, "--from", "1", "--to", "50", "--points", "20"),
           lambda s: emnet.ac(s["cantilever"], from_hz=1.0, to_hz=50.0, points=20)),
    "ac reduced": (("ac", FISHFIN, "--from", "1", "--to", "20", "--points", "20", "--reduce"),
                   lambda s: emnet.ac(s["fishfin"], from_hz=1.0, to_hz=20.0, points=20,
                                      reduce=True)),
    "tran": (("tran", FISHFIN, "--periods", "1", "--method", "exact", "--points-per-period",
              "10", "--set", "drive.electrical_dynamics=false"),
             lambda s: emnet.tran(ideal(s["fishfin"]), periods=1, method="exact",
                                  points_per_period=10)),
    "sweep_switching": (("sweep-switching", FISHFIN, "--from", "4", "--to", "6", "--step", "1"),
                        lambda s: emnet.sweep_switching(s["fishfin"], from_hz=4, to_hz=6,
                                                        step_hz=1)),
    "identify": (("identify", FISHFIN, "--resonance", "5.0"),
                 lambda s: emnet.identify(s["fishfin"], 5.0)),
    "sensitivity": (("sensitivity", FISHFIN, "--modes", "1", "--parameter",
                     "beam.bending_stiffness", "--check"),
                    lambda s: emnet.sensitivity(s["fishfin"], modes=1,
                                                parameters=["beam.bending_stiffness"],
                                                check=True)),
    "mismatch": (("mismatch", FISHFIN), lambda s: emnet.mismatch(s["fishfin"])),
    "crosscheck": (("crosscheck", CANTILEVER, "--analysis", "op"),
                   lambda s: emnet.crosscheck(s["cantilever"], analyses="op")),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_keys_are_those_of_the_command(case, fishfin, cantilever):
    arguments, call = CASES[case]
    command = key_paths(cli_json(*arguments))
    python = key_paths(call({"fishfin": fishfin, "cantilever": cantilever}))
    analysis = case.split()[0]
    assert python - command == PYTHON_ONLY.get(analysis, set())
    assert command - python == COMMAND_ONLY.get(analysis, set())


def test_the_netlist_keys_are_those_of_the_command(fishfin, tmp_path):
    command = key_paths(cli_json("netlist", FISHFIN, "--analysis", "ac", "-o",
                                 str(tmp_path / "fin.cir")))
    python = key_paths(emnet.netlist(fishfin, analysis="ac"))
    assert python - command == PYTHON_ONLY["netlist"]
    assert command - python == COMMAND_ONLY["netlist"]


def test_accuracy_and_cost_reach_both_front_ends(fishfin):
    """What each study measured of its own accuracy and cost is in the one JSON both print.

    References: identify's residual is (achieved - target) / target by definition; the nominal
    fin's pair is symmetric, so its asymmetry is zero to rounding (|x| ~ 1e-3 m, so 1e-12 is
    many ulps of slack and still far below any mismatch case's ~1e-2); a sweep of 3 frequencies
    without a check is 3 periodic solves.
    """
    fit = emnet.identify(fishfin, 5.0)
    assert fit.accuracy["frequency_residual"] == pytest.approx(
        (fit.achieved_hz - fit.target_hz) / fit.target_hz, rel=1e-12, abs=1e-15)
    assert fit.cost["modal_solves"] >= fit.iterations

    pair = emnet.mismatch(fishfin)
    assert abs(pair.nominal["asymmetry"]) < 1e-12
    assert len(pair.cases["label"]) == len(pair.cases["key"])

    sweep = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=1)
    assert sweep.cost["solves"] == 3
    assert sweep.cost["unknowns"] > 0
    assert sweep.first_mode_hz == pytest.approx(6.385, abs=5e-4)  # the paper's predicted f1
    command = cli_json("sweep-switching", FISHFIN, "--from", "4", "--to", "6", "--step", "1")
    assert command["cost"]["solves"] == sweep.cost["solves"]
    assert command["first_mode_hz"] == sweep.first_mode_hz
