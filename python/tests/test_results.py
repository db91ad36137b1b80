"""Results read as their values: repr shows each key's value in one line (numbers with their
units, arrays with their shape and first values, tables with their rows and columns), bounded."""

import numpy as np

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
