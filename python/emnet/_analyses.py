"""The analyses of one scene. Each returns a Result (see emnet.Result) with the keys of the
command's --json: the same keys in both front-ends."""

from typing import Any, Optional

from . import _emnet
from ._convert import (Flag, Integer, Number, Numbers, Texts, flag, integer, maybe_flag,
                       maybe_integer, maybe_number, number, numbers, text, texts)
from ._results import Result
from ._scene import SceneLike, as_scene


def _result(kind: str, data: dict[str, Any]) -> Result:
    """The Result of the analysis `kind` (the function's name: what to_frame reads it as)."""
    result = Result(data)
    result._kind = kind
    return result


def static(scene: SceneLike, probes: Optional[Texts] = None) -> Result:
    """The static state at rest under the drive's first half-period (as `emnet static`).

    scene: a Scene or a scene file's path. probes: probe names of the scene or texts such as
    "deflection@70mm", "rotation@0.1" (default: the scene's probes).

    Returns a Result with nodes (x_m, deflection_m, rotation_rad: numpy arrays over the beam's
    nodes), probes (name, description, unit, value), accuracy (relative_residual,
    newton_iterations), cost (seconds), validity. Nodal values are exact for any segment count.
    """
    return _result("static", _emnet.static(as_scene(scene)._handle, texts(probes, "probes")))


def modes(scene: SceneLike, count: Integer = 0, dense: Flag = False, error_estimate: Flag = True,
          shapes: Flag = False, probes: Optional[Texts] = None) -> Result:
    """The modes about the operating point (as `emnet modes`).

    count: oscillatory modes kept (0: the 10 lowest). dense: every pole by the dense method.
    error_estimate: the N/2N discretisation error of each frequency. shapes: the mode shapes.

    Returns a Result with modes: frequency_hz [Hz], natural_frequency_hz [Hz], damping_ratio
    [-], pole ([re, im] in 1/s), relative_residual, error_bounded, frequency_error_bound_hz
    [Hz] (the pole's rounding bound), discretisation_error_estimate [-] (numpy arrays, lowest
    mode first; a mode is a pair with damping ratio below 1/sqrt(2), mode_rule); overdamped_pairs;
    real_poles; rigid_body_modes; method; cost.
    """
    return _result("modes", _emnet.modes(
        as_scene(scene)._handle, integer(count, "count"), flag(dense, "dense"),
        flag(error_estimate, "error_estimate"), flag(shapes, "shapes"), texts(probes, "probes")))


def ac(scene: SceneLike, from_hz: Optional[Number] = None, to_hz: Optional[Number] = None,
       points: Optional[Integer] = None, log: Optional[Flag] = None,
       probes: Optional[Texts] = None, reduce: Flag = False, tolerance: Optional[Number] = None,
       band_hz: Optional[Number] = None) -> Result:
    """The small-signal frequency response (as `emnet ac`).

    from_hz, to_hz [Hz], points, log (a log-spaced grid): default the scene's [ac] table.
    reduce: by modal reduction, checked against the full model (tolerance, band_hz).

    Returns a Result with frequencies_hz [Hz], probes (name, description, unit, magnitude in
    the probe's unit per unit input, phase_deg [deg]; 2-D arrays [probe, frequency]), phasors
    (the complex responses, [probe, frequency]), input (what drives it), resonances_hz,
    accuracy (max_relative_residual), cost, validity.
    """
    return _result("ac", _emnet.ac(
        as_scene(scene)._handle, maybe_number(from_hz, "from_hz"), maybe_number(to_hz, "to_hz"),
        maybe_integer(points, "points"), maybe_flag(log, "log"), texts(probes, "probes"),
        flag(reduce, "reduce"), maybe_number(tolerance, "tolerance"),
        maybe_number(band_hz, "band_hz")))


def tran(scene: SceneLike, periods: Number = 10.0, switching_hz: Optional[Number] = None,
         method: str = "ida", rtol: Number = 1e-6, atol: Number = 0.0, max_step: Number = 0.0,
         start: str = "rest", points_per_period: Integer = 100, outputs: Optional[Texts] = None,
         shape_instants: Integer = 0) -> Result:
    """The time response to the scene's drive (as `emnet tran`).

    periods of the drive's frequency (or switching_hz [Hz]); method "ida" (SUNDIALS IDA, any
    network; rtol, atol, max_step [s]) or "exact" (linear networks under piecewise-linear
    sources); start "rest" or "static"; points_per_period output times per period; outputs:
    output names (dx4, u_A) or probe texts (default: the scene's recorded outputs).
    shape_instants > 0: the beam's deformed shape at that many of the last period's output
    times (shape: times_s, reference_x_m, x_m and y_m [instant, node] in metres).

    Returns a Result with times_s [s], outputs (name, description, unit, values [output,
    time]), statistics (IDA's steps, residual and Jacobian evaluations, ...), cost, validity.
    """
    return _result("tran", _emnet.tran(
        as_scene(scene)._handle, number(periods, "periods"),
        maybe_number(switching_hz, "switching_hz"), text(method, "method"), number(rtol, "rtol"),
        number(atol, "atol"), number(max_step, "max_step"), text(start, "start"),
        integer(points_per_period, "points_per_period"), texts(outputs, "outputs"),
        integer(shape_instants, "shape_instants")))


def sweep_switching(scene: SceneLike, frequencies: Optional[Numbers] = None,
                    from_hz: Number = 1.0, to_hz: Number = 7.0, step_hz: Number = 0.1,
                    method: str = "auto", samples: Integer = 0, rtol: Number = 1e-9,
                    outputs: Optional[Texts] = None, sources: Optional[Texts] = None,
                    shape_instants: Integer = 0) -> Result:
    """Periodic steady-state extremes against the switching frequency (as `emnet sweep-switching`).

    frequencies [Hz] (or from_hz, to_hz, step_hz); method "auto" (exact for a linear network,
    reduced above 1000 unknowns, shooting where a [[circuit]] drives the DEAs; the choice in the
    notes), "exact" (linear networks; DEAs as ideal voltage-driven forces, with a note) or
    "shooting" (IDA, any network; rtol). sources:
    the [[circuit]] sources whose frequency is swept (default every periodic one), each keeping
    its levels, duty, rise/fall and its delay as a fraction of the period. shape_instants > 0:
    the beam's deformed shape at that many instants over one period at the sweep peak (shape:
    frequency_hz, period_s, times_s, reference_x_m, x_m and y_m [instant, node] in metres).

    Returns a Result with scene, automatic_choices, method, notes, frequencies_hz [Hz]; outputs
    (name, description, unit, left, right: the periodic minimum (left) and maximum (right) per
    output and frequency in the output's unit, 2-D arrays [output, frequency];
    outputs.row("dx4").right is one output's); sweep_peak_hz (the largest peak-to-peak of the
    last output); first_mode_hz (the lowest mode, when found); accuracy
    (worst_periodicity_residual); cost (solves, period_runs: shooting's one-period IDA runs,
    unknowns, decomposition_seconds, solve_seconds, total_seconds); validity.
    """
    return _result("sweep_switching", _emnet.sweep_switching(
        as_scene(scene)._handle, numbers(frequencies, "frequencies"), number(from_hz, "from_hz"),
        number(to_hz, "to_hz"), number(step_hz, "step_hz"), text(method, "method"),
        integer(samples, "samples"), number(rtol, "rtol"), texts(outputs, "outputs"),
        texts(sources, "sources"), integer(shape_instants, "shape_instants")))


def identify(scene: SceneLike, target_hz: Number, parameter: str = "beam.bending_stiffness",
             mode: Integer = 1) -> Result:
    """The value of `parameter` that puts mode `mode` at target_hz [Hz] (as `emnet identify`).

    Returns a Result with automatic_choices, parameter (its canonical key), value and unit (SI),
    mode, target_hz and achieved_hz [Hz], iterations (modal solves of the fit), accuracy
    (frequency_residual: (achieved - target) / target), cost (modal_solves, periodic_solves),
    command (this call, for the scene's [provenance]), total_seconds, notes (when there are any).
    """
    return _result("identify", _emnet.identify(
        as_scene(scene)._handle, number(target_hz, "target_hz"), text(parameter, "parameter"),
        integer(mode, "mode")))


def sensitivity(scene: SceneLike, modes: Integer = 3, parameters: Optional[Texts] = None,
                check: Flag = False) -> Result:
    """d f/d p of the lowest `modes` resonances for every parameter (as `emnet sensitivity`).

    parameters: keys (default: every parameter the scene uses). check: also the finite
    difference of the poles.

    Returns a Result with modes (frequency_hz, ...), parameters (key, value, unit, and per mode
    the derivatives [Hz per unit] and normalised sensitivities (p/f) df/dp [-]), cost.
    """
    return _result("sensitivity", _emnet.sensitivity(
        as_scene(scene)._handle, integer(modes, "modes"), texts(parameters, "parameters"),
        flag(check, "check")))


def mismatch(scene: SceneLike, frequency_hz: Optional[Number] = None, output: str = "",
             change: Number = 0.05) -> Result:
    """Left/right asymmetry of the periodic peaks when one DEA differs by ±change (as `emnet
    mismatch`): electrode area, film thickness, overlap.

    Returns a Result with automatic_choices, output, frequency_hz, method ("exact", or
    "shooting" with large kinematics), nominal (left_m, right_m,
    asymmetry [-]), cases (label, key, change, left_m, right_m, asymmetry [-],
    asymmetry_per_unit_change),
    total_seconds, validity, notes (when there are any).
    """
    return _result("mismatch", _emnet.mismatch(
        as_scene(scene)._handle, maybe_number(frequency_hz, "frequency_hz"),
        text(output, "output"), number(change, "change")))


def netlist(scene: SceneLike, analysis: str = "op", periods: Number = 2.0,
            points_per_period: Integer = 2000, rtol: Number = 1e-6,
            control: Flag = False) -> Result:
    """The scene's network as a SPICE deck (as `emnet netlist`): analysis "op", "ac" or "tran".

    Returns a Result with text (the deck; the command writes it to a file and names that
    "deck" instead), automatic_choices, analysis, unknowns (name, vector, sign: where ngspice
    holds each unknown), outputs (probe, vector, unit, description), notes.
    """
    return _result("netlist", _emnet.netlist(
        as_scene(scene)._handle, text(analysis, "analysis"), number(periods, "periods"),
        integer(points_per_period, "points_per_period"), number(rtol, "rtol"),
        flag(control, "control")))


def crosscheck(scene: SceneLike, analyses: str = "all", timeout: Number = 60.0) -> Result:
    """emnet against ngspice on the same network (as `emnet crosscheck`): "op,ac,modal,tran".

    ngspice runs in its own worker process (timeout [s]). Returns a Result with scene,
    automatic_choices, backend, status, pass (every difference within its tolerance), rows
    (analysis, quantity, largest_difference, where, tolerance, pass, basis), timings, notes,
    total_seconds.
    """
    return _result("crosscheck", _emnet.crosscheck(
        as_scene(scene)._handle, text(analyses, "analyses"), number(timeout, "timeout")))
