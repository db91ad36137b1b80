"""Every binding against the command line's numbers.

Reference: `emnet COMMAND --json` on the same scene. Both call the same library function on the
same scene, and the JSON writer prints doubles so that they read back exactly, so the values must
be equal, not close: any difference is a front-end that computes something else.
"""

import numpy

import emnet
from conftest import CANTILEVER, FISHFIN, cli_json


def test_static_equals_the_command(cantilever):
    result = emnet.static(cantilever)
    reference = cli_json("static", CANTILEVER)
    nodes = reference["nodes"]
    assert isinstance(result.nodes["x_m"], numpy.ndarray)
    assert list(result.nodes["x_m"]) == [n["x_m"] for n in nodes]
    assert list(result.nodes["deflection_m"]) == [n["deflection_m"] for n in nodes]
    assert list(result.probes["value"]) == [p["value"] for p in reference["probes"]]
    # And the closed form, F*L^3/(3*EI) = 20.833 mm: nodal statics are exact (rounding only).
    tip = result.probes["value"][list(result.probes["name"]).index("tip")]
    assert abs(tip - 1.0 * 0.5**3 / (3 * 2.0)) < 1e-12


def test_modes_equal_the_command(fishfin):
    result = emnet.modes(fishfin, count=3)
    reference = cli_json("modes", FISHFIN, "--count", "3")
    assert list(result.modes["frequency_hz"]) == [m["frequency_hz"] for m in reference["modes"]]
    assert list(result.modes["damping_ratio"]) == [m["damping_ratio"] for m in reference["modes"]]
    # The paper's network resonance, 6.385 Hz: EI was identified to it and is stored with 7
    # significant digits, so f1 ~ sqrt(EI) holds it to about 5e-8 relative; 1e-6 leaves room.
    assert abs(result.modes["frequency_hz"][0] - 6.385) < 6.385 * 1e-6


def test_ac_equals_the_command(cantilever):
    result = emnet.ac(cantilever, from_hz=1.0, to_hz=50.0, points=20)
    reference = cli_json("ac", CANTILEVER, "--from", "1", "--to", "50", "--points", "20")
    assert list(result.frequencies_hz) == reference["frequencies_hz"]
    for k, probe in enumerate(reference["probes"]):
        assert list(result.probes["magnitude"][k]) == probe["magnitude"]
        assert list(result.probes["phase_deg"][k]) == probe["phase_deg"]
    assert numpy.allclose(numpy.abs(result.phasors), result.probes["magnitude"], rtol=1e-15,
                          atol=0)


def test_tran_equals_the_command(fishfin):
    # The exact method needs a linear network: the DEAs as ideal voltage-driven forces.
    ideal = fishfin.with_overrides({"drive.electrical_dynamics": False})
    result = emnet.tran(ideal, periods=2, method="exact", points_per_period=20)
    reference = cli_json("tran", FISHFIN, "--periods", "2", "--method", "exact",
                         "--points-per-period", "20", "--set", "drive.electrical_dynamics=false")
    assert list(result.times_s) == reference["times_s"]
    for k, output in enumerate(reference["outputs"]):
        assert list(result.outputs["values"][k]) == output["values"]


def test_sweep_switching_equals_the_command(fishfin):
    result = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=0.5)
    reference = cli_json("sweep-switching", FISHFIN, "--from", "4", "--to", "6", "--step", "0.5")
    assert list(result.frequencies_hz) == reference["frequencies_hz"]
    assert list(result.outputs["name"]) == [output["name"] for output in reference["outputs"]]
    for k, output in enumerate(reference["outputs"]):
        assert list(result.outputs["left"][k]) == output["left"]
        assert list(result.outputs.row(output["name"]).right) == output["right"]
    assert result.sweep_peak_hz == reference["sweep_peak_hz"]


def test_identify_equals_the_command(fishfin):
    result = emnet.identify(fishfin, 5.0)
    reference = cli_json("identify", FISHFIN, "--resonance", "5.0")
    assert result.value == reference["value"]
    assert result.achieved_hz == reference["achieved_hz"]
    assert abs(result.achieved_hz - 5.0) <= 5.0 * 1e-9


def test_sensitivity_equals_the_command(fishfin):
    keys = ["beam.bending_stiffness", "beam.mass_per_length"]
    result = emnet.sensitivity(fishfin, modes=1, parameters=keys)
    reference = cli_json("sensitivity", FISHFIN, "--modes", "1", "--parameter", keys[0],
                         "--parameter", keys[1])
    assert list(result.parameters["key"]) == [p["key"] for p in reference["parameters"]]
    for mine, theirs in zip(result.parameters["modes"], reference["parameters"]):
        assert list(mine["frequency_derivative"]) == \
            [m["frequency_derivative"] for m in theirs["modes"]]
    # Closed form: every natural frequency of the beam is sqrt(EI/rhoA) times a constant, so
    # (p/f) df/dp = +1/2 for EI and -1/2 for rhoA; the matrices are differenced at p(1 +/- 1e-6),
    # whose truncation (1e-12) and rounding (1e-16/1e-6 = 1e-10) errors lie far below 1e-8.
    natural = [m["normalised_natural"][0] for m in result.parameters["modes"]]
    assert abs(natural[0] - 0.5) < 1e-8
    assert abs(natural[1] + 0.5) < 1e-8


def test_mismatch_equals_the_command(fishfin):
    result = emnet.mismatch(fishfin)
    reference = cli_json("mismatch", FISHFIN)
    assert list(result.cases["asymmetry"]) == [c["asymmetry"] for c in reference["cases"]]
    assert result.nominal.left_m == reference["nominal"]["left_m"]


def test_netlist_equals_the_command(fishfin, tmp_path):
    deck = emnet.netlist(fishfin, analysis="ac")
    path = tmp_path / "fin.cir"
    import subprocess
    from conftest import PROGRAM
    subprocess.run([PROGRAM, "netlist", FISHFIN, "--analysis", "ac", "-o", str(path), "--quiet"],
                   check=True, capture_output=True)
    assert deck.text == path.read_text()


def test_crosscheck_op_passes_as_the_command(cantilever):
    result = emnet.crosscheck(cantilever, analyses="op")
    reference = cli_json("crosscheck", CANTILEVER, "--analysis", "op")
    assert result["pass"] == reference["pass"] is True
    assert list(result.rows["quantity"]) == [r["quantity"] for r in reference["rows"]]


def test_sweep_shape_equals_the_command(fishfin, tmp_path):
    result = emnet.sweep_switching(fishfin, frequencies=[6.4], shape_instants=4)
    reference = cli_json("sweep-switching", FISHFIN, "--from", "6.4", "--to", "6.4",
                         "--shape", str(tmp_path / "shape.csv"), "--shape-instants", "4")
    import numpy
    shape = result["shape"]
    assert numpy.asarray(shape["times_s"]).tolist() == reference["shape"]["times_s"]
    assert numpy.asarray(shape["y_m"]).tolist() == reference["shape"]["y_m"]
    assert numpy.asarray(shape["y_m"]).shape == (4, 8)


def test_tran_shape_equals_the_command(fishfin, tmp_path):
    import numpy
    result = emnet.tran(fishfin, periods=1, shape_instants=4)
    reference = cli_json("tran", FISHFIN, "--periods", "1", "--shape", str(tmp_path / "s.csv"),
                         "--shape-instants", "4")
    assert numpy.asarray(result["shape"]["y_m"]).tolist() == reference["shape"]["y_m"]
    assert numpy.asarray(result["shape"]["y_m"]).shape == (4, 8)
