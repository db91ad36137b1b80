"""Results read as their values: repr shows each key's value in one line (numbers with their
units, arrays with their shape and first values, tables with their rows and columns), bounded;
to_frame gives a result's table as a DataFrame, to_xarray its arrays over outputs as a Dataset.
Every value is checked against the result's own arrays: they are the command's numbers
(test_bindings.py)."""

import pickle

import numpy as np
import pandas as pd
import pytest

import emnet


def _line(result, key):
    """The line of repr(result) that shows `key`."""
    found = [line for line in repr(result).splitlines() if line.split()[:1] == [key]]
    assert len(found) == 1, repr(result)
    return found[0].split(None, 1)[1]


def test_repr_shows_scalars_arrays_and_tables_with_units(cantilever):
    result = emnet.ac(cantilever, from_hz=1, to_hz=50, points=5)
    text = repr(result)
    assert text.splitlines()[0] == "emnet.ac result:"
    assert _line(result, "segments") == "20"
    f = result.frequencies_hz
    assert _line(result, "frequencies_hz") == \
        f"array(5) [{f[0]:.6g}, {f[1]:.6g}, {f[2]:.6g}, {f[3]:.6g}, {f[4]:.6g}] Hz"
    # (a line longer than 100 characters ends in an ellipsis)
    assert _line(result, "probes") == ("table of 2 rows (tip [m], mid [m]): name, description, "
                                       "unit, magnitude(2×5), p…")
    assert _line(result, "accuracy") == \
        f"{{max_relative_residual: {result.accuracy.max_relative_residual:.6g}, method: 'direct'}}"
    assert _line(result, "input") == repr(result.input[:59] + "…")


def test_repr_elides_long_arrays(fishfin):
    result = emnet.tran(fishfin, periods=2, points_per_period=500)
    t = result.times_s
    assert len(t) == 1001
    assert _line(result, "times_s") == \
        f"array(1001) [{t[0]:.6g}, {t[1]:.6g}, {t[2]:.6g}, {t[3]:.6g}, …, {t[-1]:.6g}] s"
    values = result.outputs["values"]
    assert _line(result.outputs, "values") == (
        f"array(8×1001) [{values[0, 0]:.6g}, {values[0, 1]:.6g}, {values[0, 2]:.6g}, "
        f"{values[0, 3]:.6g}, …, {values[-1, -1]:.6g}]")
    assert repr(result.outputs).splitlines()[0] == "Result, a table of 8 rows:"


def test_repr_gives_a_records_unit_to_its_values(fishfin):
    sweep = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=1)
    right = sweep.outputs.row("dx4").right
    assert _line(sweep.outputs.row("dx4"), "right") == \
        f"array(3) [{right[0]:.6g}, {right[1]:.6g}, {right[2]:.6g}] m"
    assert _line(sweep, "sweep_peak_hz") == f"{sweep.sweep_peak_hz:.6g} Hz"
    fit = emnet.identify(fishfin, 5.0)
    assert _line(fit, "value") == f"{fit.value:.6g} N*m^2"
    assert _line(fit, "mode") == "1"


def test_repr_is_bounded_for_every_analysis(fishfin, cantilever):
    results = [emnet.static(cantilever), emnet.modes(fishfin, shapes=True, probes=["P4"]),
               emnet.ac(fishfin, points=2000), emnet.tran(fishfin, periods=3),
               emnet.sweep_switching(fishfin), emnet.identify(fishfin, 5.0),
               emnet.sensitivity(fishfin), emnet.mismatch(fishfin), emnet.netlist(fishfin),
               emnet.crosscheck(cantilever, analyses="op")]
    for result in results:
        lines = repr(result).splitlines()
        assert len(lines) == len(result) + 1
        assert max(len(line) for line in lines) <= 100, repr(result)
    many = emnet.Result({f"key{k}": np.arange(10**5) * 1.0 for k in range(100)})
    lines = repr(many).splitlines()
    assert len(lines) == 40
    assert lines[-1] == "  … and 62 more keys"
    assert lines[1] == "  key0   array(100000) [0, 1, 2, 3, …, 99999]"


# ---- DataFrames: each analysis's table; any table inside a result by name --------------------

def test_static_frame_is_its_probes(cantilever):
    result = emnet.static(cantilever)
    frame = result.to_frame()
    assert list(frame.columns) == ["name", "description", "unit", "value"]
    assert frame["name"].tolist() == ["tip", "mid"]
    assert frame["value"].tolist() == list(result.probes["value"])
    # F*L^3/(3*EI) at the tip (exact nodal statics).
    assert abs(frame.set_index("name").loc["tip", "value"] - 0.5**3 / (3 * 2.0)) < 1e-13


def test_modes_frame_has_a_row_per_mode(fishfin):
    result = emnet.modes(fishfin, count=3, shapes=True)
    frame = result.to_frame()
    assert frame.index.name == "mode" and frame.index.tolist() == [1, 2, 3]
    assert frame["frequency_hz"].tolist() == list(result.modes["frequency_hz"])
    assert frame["damping_ratio"].tolist() == list(result.modes["damping_ratio"])
    assert frame["pole_real"].tolist() == list(result.modes["pole"][:, 0])
    assert frame["pole_imag"].tolist() == list(result.modes["pole"][:, 1])
    assert "shape" not in frame.columns  # a mode shape per row stays in the result
    assert frame.attrs["units"]["frequency_hz"] == "Hz"
    assert frame.attrs["units"]["pole_imag"] == "1/s"
    # The paper's first resonance, and f = |Im pole| / (2 pi).
    assert abs(frame.loc[1, "frequency_hz"] - 6.385) < 6.385e-6
    assert np.allclose(frame["frequency_hz"], frame["pole_imag"] / (2 * np.pi), rtol=1e-12)


def test_ac_frame_has_a_row_per_frequency(cantilever):
    result = emnet.ac(cantilever, from_hz=1, to_hz=50, points=7)
    frame = result.to_frame()
    assert frame.index.name == "frequency_hz"
    assert frame.index.tolist() == list(result.frequencies_hz)
    assert list(frame.columns) == ["tip_magnitude", "tip_phase_deg", "mid_magnitude",
                                   "mid_phase_deg"]
    assert frame["mid_magnitude"].tolist() == list(result.probes["magnitude"][1])
    assert frame["tip_phase_deg"].tolist() == list(result.probes["phase_deg"][0])
    assert frame.attrs["units"] == {"frequency_hz": "Hz", "tip_magnitude": "m",
                                    "tip_phase_deg": "deg", "mid_magnitude": "m",
                                    "mid_phase_deg": "deg"}


def test_tran_frame_has_a_row_per_time(fishfin):
    result = emnet.tran(fishfin, periods=1, points_per_period=20)
    frame = result.to_frame()
    assert frame.index.name == "times_s" and frame.index.tolist() == list(result.times_s)
    assert list(frame.columns) == list(result.outputs["name"])
    assert frame["u_A"].tolist() == list(result.outputs.row("u_A")["values"])
    assert frame.attrs["units"]["dx4"] == "m" and frame.attrs["units"]["u_A"] == "V"
    assert frame.attrs["units"]["times_s"] == "s"


def test_sweep_frame_has_min_and_max_per_output(fishfin):
    result = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=0.5)
    frame = result.to_frame()
    assert frame.index.name == "frequency_hz"
    assert frame.index.tolist() == [4.0, 4.5, 5.0, 5.5, 6.0]
    names = list(result.outputs["name"])
    assert list(frame.columns) == [f"{n}_{m}" for n in names for m in ("min", "max")]
    assert frame["dx4_min"].tolist() == list(result.outputs.row("dx4").left)
    assert frame["dx4_max"].tolist() == list(result.outputs.row("dx4").right)
    assert frame.attrs["units"]["tip_max"] == "m"
    assert frame["dx4_max"].idxmax() == 6.0  # nearest the 6.385 Hz resonance


def test_sensitivity_frame_has_a_row_per_parameter_and_mode(fishfin):
    keys = ["beam.bending_stiffness", "beam.mass_per_length"]
    result = emnet.sensitivity(fishfin, modes=2, parameters=keys)
    frame = result.to_frame()
    assert frame["parameter"].tolist() == [keys[0], keys[0], keys[1], keys[1]]
    assert frame["mode"].tolist() == [1, 2, 1, 2]
    assert frame["unit"].tolist() == ["N*m^2", "N*m^2", "kg/m", "kg/m"]
    assert frame["frequency_hz"].tolist() == list(result.modes["frequency_hz"]) * 2
    for row in range(4):
        per_mode = result.parameters["modes"][row // 2]
        assert frame["frequency_derivative"][row] == per_mode["frequency_derivative"][row % 2]
    # (p/f) df/dp = +1/2 for EI and -1/2 for the mass per length (test_bindings.py).
    assert np.allclose(frame["normalised_natural"], [0.5, 0.5, -0.5, -0.5], atol=1e-8)
    assert frame.attrs["units"]["frequency_derivative"] == "Hz per unit of the parameter"
    assert frame.attrs["units"]["frequency_hz"] == "Hz"


def test_mismatch_and_crosscheck_frames_are_their_tables(fishfin, cantilever):
    pair = emnet.mismatch(fishfin)
    assert pair.to_frame()["asymmetry"].tolist() == list(pair.cases["asymmetry"])
    assert pair.to_frame().attrs["units"]["left_m"] == "m"
    check = emnet.crosscheck(cantilever, analyses="op")
    assert check.to_frame()["quantity"].tolist() == list(check.rows["quantity"])
    assert check.to_frame()["pass"].all()


def test_any_table_reads_by_name_or_by_itself(cantilever, fishfin):
    result = emnet.static(cantilever)
    nodes = result.to_frame("nodes")
    assert nodes["x_m"].tolist() == list(result.nodes["x_m"])
    assert nodes.attrs["units"] == {"x_m": "m", "deflection_m": "m", "rotation_rad": "rad"}
    pd.testing.assert_frame_equal(result.nodes.to_frame(), nodes)
    deck = emnet.netlist(fishfin)
    assert deck.to_frame("outputs")["probe"].tolist() == list(deck.outputs["probe"])


def test_a_column_some_records_lack_reads_and_stays_out_of_the_frame():
    # A key some records lack is a list with None where it is missing (bindings' to_python).
    result = emnet.Result({"rows": {"name": ["a", "b"], "x_m": np.array([1.0, 2.0]),
                                    "shape": [np.array([1.0, 2.0, 3.0]), None]}})
    assert _line(result, "rows") == "table of 2 rows: name, x_m, shape"
    frame = result.to_frame("rows")
    assert list(frame.columns) == ["name", "x_m"]
    assert frame["x_m"].tolist() == [1.0, 2.0]


def test_a_result_without_a_table_says_which_have_one(fishfin):
    with pytest.raises(TypeError) as error:
        emnet.identify(fishfin, 5.0).to_frame()
    assert str(error.value).startswith("to_frame(): an emnet.identify result has no table")
    assert "static, modes, ac, tran, sweep_switching" in str(error.value)
    with pytest.raises(TypeError) as error:
        emnet.netlist(fishfin).to_frame()
    assert "to_frame('unknowns') or to_frame('outputs')" in str(error.value)
    with pytest.raises(ValueError) as error:
        emnet.netlist(fishfin).to_frame("nodes")
    assert str(error.value) == "this result has no table 'nodes'; its tables are: unknowns, outputs"


def test_a_pickled_result_keeps_its_table(cantilever):
    result = emnet.ac(cantilever, from_hz=1, to_hz=50, points=5)
    again = pickle.loads(pickle.dumps(result))
    pd.testing.assert_frame_equal(again.to_frame(), result.to_frame())
    assert repr(again).splitlines()[0] == "emnet.ac result:"


# ---- xarray: arrays over outputs and frequency or time ---------------------------------------

def test_ac_dataset(cantilever):
    result = emnet.ac(cantilever, from_hz=1, to_hz=50, points=7)
    data = result.to_xarray()
    assert dict(data.sizes) == {"output": 2, "frequency": 7}
    assert data["magnitude"].dims == ("output", "frequency")
    assert data["output"].values.tolist() == ["tip", "mid"]
    assert data["frequency_hz"].values.tolist() == list(result.frequencies_hz)
    assert data["frequency_hz"].attrs["units"] == "Hz"
    assert (data["magnitude"].values == result.probes["magnitude"]).all()
    assert (data["phase_deg"].values == result.probes["phase_deg"]).all()
    assert (data["phasor"].values == result.phasors).all()
    assert data["magnitude"].attrs["units"] == "m" and data["phase_deg"].attrs["units"] == "deg"
    f = result.frequencies_hz[3]
    assert data["magnitude"].sel(output="mid", frequency_hz=f).item() == \
        result.probes["magnitude"][1][3]
    assert data.attrs["analysis"] == "emnet.ac" and data.attrs["scene"] == "cantilever"


def test_sweep_dataset(fishfin):
    result = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=1)
    data = result.to_xarray()
    assert data["minimum"].dims == ("output", "frequency")
    assert (data["minimum"].values == result.outputs["left"]).all()
    assert (data["maximum"].values == result.outputs["right"]).all()
    assert data["maximum"].sel(output="dx4", frequency_hz=5.0).item() == \
        result.outputs.row("dx4").right[1]
    assert data["maximum"].attrs["units"] == "m"
    assert data.attrs["sweep_peak_hz"] == result.sweep_peak_hz


def test_tran_dataset(fishfin):
    result = emnet.tran(fishfin, periods=1, points_per_period=20)
    data = result.to_xarray()
    assert data["value"].dims == ("output", "time")
    assert data["times_s"].values.tolist() == list(result.times_s)
    assert (data["value"].values == result.outputs["values"]).all()
    # Outputs of several units: each output's unit is a coordinate, no unit for the whole.
    assert data["unit"].sel(output="u_A").item() == "V"
    assert "units" not in data["value"].attrs


def test_to_xarray_says_which_results_have_arrays(fishfin):
    with pytest.raises(TypeError) as error:
        emnet.modes(fishfin).to_xarray()
    assert str(error.value).startswith("to_xarray(): an emnet.modes result has no arrays")
    assert "ac, sweep_switching and tran" in str(error.value)
