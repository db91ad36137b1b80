"""The analyses of one scene. Each returns a Result (see emnet.Result) with the keys of the
command's --json: the same keys in both front-ends."""

from typing import Any, Optional

from . import _emnet
from ._convert import (Flag, Integer, Number, Numbers, Texts, flag, integer, maybe_flag,
                       maybe_integer, maybe_number, number, numbers, text, texts)
from ._command import program
from ._results import Result
from ._scene import SceneLike, as_scene


def _result(kind: str, data: dict[str, Any]) -> Result:
    """The Result of the analysis `kind` (the function's name: what to_frame reads it as)."""
    result = Result(data)
    result._kind = kind
    return result


def static(scene: SceneLike, probes: Optional[Texts] = None) -> Result:
    """The static state at rest under the drive's first half-period (as `emnet static`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    probes : str or sequence of str, optional
        Probe names of the scene, or texts such as "deflection@70mm", "rotation@0.1" (default:
        the scene's probes).

    Returns
    -------
    Result
        nodes: x_m [m], deflection_m [m], rotation_rad [rad], arrays over the beam's nodes (exact
        at the nodes for any segment count); probes: name, description, unit, value [the probe's
        unit]; accuracy: relative_residual [-], newton_iterations; cost [s]; validity.
        result.to_frame(): the probes, a row each.

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("static", _emnet.static(as_scene(scene)._handle, texts(probes, "probes")))


def modes(scene: SceneLike, count: Integer = 0, dense: Flag = False, error_estimate: Flag = True,
          shapes: Flag = False, probes: Optional[Texts] = None) -> Result:
    """The modes about the operating point (as `emnet modes`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    count : int, default 0
        Oscillatory modes kept (0: the 10 lowest).
    dense : bool, default False
        Every pole by the dense method.
    error_estimate : bool, default True
        The N/2N discretisation error of each frequency [-].
    shapes : bool, default False
        The mode shapes: x_m [m], deflection and deflection_imag [-] (the largest deflection 1).
    probes : str or sequence of str, optional
        With shapes, each probe's value in each shape [the probe's unit per unit largest
        deflection].

    Returns
    -------
    Result
        modes: frequency_hz [Hz], natural_frequency_hz [Hz], damping_ratio [-], pole ([re, im]
        [1/s]), relative_residual [-], error_bounded, frequency_error_bound_hz [Hz] (the pole's
        rounding bound), discretisation_error_estimate [-]: arrays, lowest mode first (a mode is a
        pole pair with damping ratio below 1/sqrt(2): mode_rule); overdamped_pairs; real_poles
        (pole [1/s], time_constant_s [s]); rigid_body_modes; method; cost [s].
        result.to_frame(): a row per mode (index mode, from 1; pole_real, pole_imag [1/s]).

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("modes", _emnet.modes(
        as_scene(scene)._handle, integer(count, "count"), flag(dense, "dense"),
        flag(error_estimate, "error_estimate"), flag(shapes, "shapes"), texts(probes, "probes")))


def ac(scene: SceneLike, from_hz: Optional[Number] = None, to_hz: Optional[Number] = None,
       points: Optional[Integer] = None, log: Optional[Flag] = None,
       probes: Optional[Texts] = None, reduce: Flag = False, tolerance: Optional[Number] = None,
       band_hz: Optional[Number] = None, method: str = "auto") -> Result:
    """The small-signal frequency response (as `emnet ac`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    from_hz, to_hz : float, optional
        The first and last frequency [Hz] (default: the scene's [ac] table).
    points : int, optional
        Frequencies in the grid (default: the scene's [ac] table).
    log : bool, optional
        A log-spaced grid (default: the scene's [ac] table).
    probes : str or sequence of str, optional
        Probe names or texts (default: the scene's probes).
    reduce : bool, default False
        By modal reduction, checked against the full model (method "reduced").
    tolerance : float, optional
        The reduction's tolerance [-] (default: the scene's model.tolerance).
    band_hz : float, optional
        The band the reduced model keeps [Hz] (default: to_hz).
    method : {"auto", "full", "reduced"}, default "auto"
        "auto": the modal reduction above 2000 unknowns for 500 frequencies or more, kept only
        when its check against the full model meets the tolerance (a note says which); "full":
        every frequency on the full model; "reduced": the modal reduction whatever its check.

    Returns
    -------
    Result
        frequencies_hz [Hz]; probes: name, description, unit, magnitude [the probe's unit per unit
        input] and phase_deg [deg], 2-D arrays [probe, frequency]; phasors: the complex responses
        [probe, frequency]; input (what drives it); resonances_hz [Hz]; accuracy
        (method; max_relative_residual [-] of the full model's solves, or the reduction's
        measured_error [-] against the full model); notes; cost [s]; validity.
        result.to_frame(): a row per frequency, <probe>_magnitude and <probe>_phase_deg;
        result.to_xarray(): magnitude, phase_deg and phasor over (output, frequency).

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("ac", _emnet.ac(
        as_scene(scene)._handle, maybe_number(from_hz, "from_hz"), maybe_number(to_hz, "to_hz"),
        maybe_integer(points, "points"), maybe_flag(log, "log"), texts(probes, "probes"),
        flag(reduce, "reduce"), maybe_number(tolerance, "tolerance"),
        maybe_number(band_hz, "band_hz"), text(method, "method")))


def tran(scene: SceneLike, periods: Number = 10.0, switching_hz: Optional[Number] = None,
         method: str = "ida", rtol: Number = 1e-6, atol: Number = 0.0, max_step: Number = 0.0,
         start: str = "rest", points_per_period: Integer = 100, outputs: Optional[Texts] = None,
         shape_instants: Integer = 0) -> Result:
    """The time response to the scene's drive (as `emnet tran`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    periods : float, default 10
        The duration, in periods of the drive's frequency (or of switching_hz) [-].
    switching_hz : float, optional
        The drive's switching frequency [Hz] (default: the scene's drive.frequency).
    method : {"ida", "exact"}, default "ida"
        "ida": SUNDIALS IDA, any network; "exact": linear networks under piecewise-linear
        sources.
    rtol : float, default 1e-6
        IDA's relative tolerance [-].
    atol : float, default 0
        IDA's absolute tolerance [the unknown's unit] (0: rtol times a scale per unknown).
    max_step : float, default 0
        IDA's largest step [s] (0: no limit).
    start : {"rest", "static"}, default "rest"
        The state at t = 0: at rest, or the static state.
    points_per_period : int, default 100
        Output times per period.
    outputs : str or sequence of str, optional
        Output names (dx4, u_A) or probe texts (default: the scene's recorded outputs).
    shape_instants : int, default 0
        > 0: the beam's deformed shape at that many of the last period's output times (shape:
        times_s [s], reference_x_m [m], x_m and y_m [instant, node] [m]).

    Returns
    -------
    Result
        times_s [s]; outputs: name, description, unit, values [output, time] [the output's unit];
        statistics (IDA's steps, residual and Jacobian evaluations, ...); cost [s]; validity.
        result.to_frame(): a row per time (index times_s), a column per output;
        result.to_xarray(): value over (output, time).

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
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

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    frequencies : sequence of float, optional
        The switching frequencies [Hz] (default: from_hz to to_hz in steps of step_hz).
    from_hz, to_hz, step_hz : float, default 1, 7, 0.1
        The grid without `frequencies` [Hz].
    method : {"auto", "exact", "shooting"}, default "auto"
        "auto": exact for a linear network, reduced above 1000 unknowns, the exact cascade
        where a [[circuit]] drives the DEAs and their force is the only nonlinearity, shooting
        where it is not (back-coupling, large kinematics; the choice in the notes); "exact":
        linear networks (DEAs as ideal voltage-driven forces, with a note) and cascades;
        "shooting": IDA, any network.
    samples : int, default 0
        Samples per period (0: 64 exact, 256 shooting; from 8 to 1000000).
    rtol : float, default 1e-9
        Shooting's IDA relative tolerance [-].
    outputs : str or sequence of str, optional
        Output names or probe texts (default: the scene's recorded outputs).
    sources : str or sequence of str, optional
        The [[circuit]] sources whose frequency is swept (default: every periodic one), each
        keeping its levels, duty, rise/fall and its delay as a fraction of the period.
    shape_instants : int, default 0
        > 0: the beam's deformed shape at that many instants over one period at the sweep peak
        (shape: frequency_hz [Hz], period_s [s], times_s [s], reference_x_m [m], x_m and y_m
        [instant, node] [m]).

    Returns
    -------
    Result
        scene, automatic_choices, method, notes, frequencies_hz [Hz]; outputs: name, description,
        unit, left and right, the periodic minimum (left) and maximum (right) [the output's unit],
        2-D arrays [output, frequency] (outputs.row("dx4").right is one output's); sweep_peak_hz
        [Hz] (the largest peak-to-peak of the last output); first_mode_hz [Hz] (the lowest mode,
        when found); accuracy (worst_periodicity_residual [-]); cost (solves, period_runs:
        shooting's one-period IDA runs, unknowns, decomposition_seconds, solve_seconds,
        total_seconds [s]); validity.
        result.to_frame(): a row per frequency, <output>_min and <output>_max;
        result.to_xarray(): minimum and maximum over (output, frequency).

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("sweep_switching", _emnet.sweep_switching(
        as_scene(scene)._handle, numbers(frequencies, "frequencies"), number(from_hz, "from_hz"),
        number(to_hz, "to_hz"), number(step_hz, "step_hz"), text(method, "method"),
        integer(samples, "samples"), number(rtol, "rtol"), texts(outputs, "outputs"),
        texts(sources, "sources"), integer(shape_instants, "shape_instants")))


def identify(scene: SceneLike, target_hz: Number, parameter: str = "beam.bending_stiffness",
             mode: Integer = 1) -> Result:
    """The value of `parameter` that puts mode `mode` at target_hz (as `emnet identify`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    target_hz : float
        The frequency the mode is to have [Hz].
    parameter : str, default "beam.bending_stiffness"
        The numeric key fitted.
    mode : int, default 1
        The mode, from 1 (the lowest).

    Returns
    -------
    Result
        automatic_choices; parameter (its canonical key); value and unit [SI]; mode; target_hz and
        achieved_hz [Hz]; iterations (modal solves of the fit); accuracy (frequency_residual [-]:
        (achieved - target) / target); cost (modal_solves, periodic_solves); command (this call,
        for the scene's [provenance]); total_seconds [s]; notes (when there are any).

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("identify", _emnet.identify(
        as_scene(scene)._handle, number(target_hz, "target_hz"), text(parameter, "parameter"),
        integer(mode, "mode")))


def sensitivity(scene: SceneLike, modes: Integer = 3, parameters: Optional[Texts] = None,
                check: Flag = False) -> Result:
    """d f/d p of the lowest `modes` resonances for every parameter (as `emnet sensitivity`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    modes : int, default 3
        The resonances, lowest first.
    parameters : str or sequence of str, optional
        Numeric keys (default: every parameter the scene uses).
    check : bool, default False
        Also the finite difference of the poles.

    Returns
    -------
    Result
        modes (frequency_hz [Hz], natural_frequency_hz [Hz], pole [1/s]); parameters: key, value,
        unit, and per mode the derivatives [Hz per the parameter's unit] and the normalised
        sensitivities (p/f) df/dp [-]; cost [s].
        result.to_frame(): a row per parameter and mode.

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("sensitivity", _emnet.sensitivity(
        as_scene(scene)._handle, integer(modes, "modes"), texts(parameters, "parameters"),
        flag(check, "check")))


def mismatch(scene: SceneLike, frequency_hz: Optional[Number] = None, output: str = "",
             change: Number = 0.05) -> Result:
    """Left/right asymmetry of the periodic peaks when a DEA differs by ±change (`emnet mismatch`).

    Electrode area, film thickness and the switching overlap are changed in turn.

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    frequency_hz : float, optional
        The switching frequency [Hz] (default: the scene's drive.frequency).
    output : str, default ""
        An output name or probe text ("": the last dx_k, dx4 on the fish fin).
    change : float, default 0.05
        The relative change of each parameter [-], in (0, 0.5).

    Returns
    -------
    Result
        automatic_choices, output, frequency_hz [Hz], method ("exact", or "shooting" with large
        kinematics); nominal (left_m, right_m [m], asymmetry [-]); cases: label, key, change [-],
        left_m, right_m [m], asymmetry [-], asymmetry_per_unit_change [-]; total_seconds [s];
        validity; notes (when there are any).
        result.to_frame(): the cases, a row each.

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("mismatch", _emnet.mismatch(
        as_scene(scene)._handle, maybe_number(frequency_hz, "frequency_hz"),
        text(output, "output"), number(change, "change")))


def netlist(scene: SceneLike, analysis: str = "op", periods: Number = 2.0,
            points_per_period: Integer = 2000, rtol: Number = 1e-6,
            control: Flag = False) -> Result:
    """The scene's network as a SPICE deck (as `emnet netlist`).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    analysis : {"op", "ac", "tran"}, default "op"
        The deck's analysis.
    periods : float, default 2
        tran: the duration in periods of the drive [-].
    points_per_period : int, default 2000
        tran: output steps per period.
    rtol : float, default 1e-6
        ngspice's relative tolerance [-].
    control : bool, default False
        Append an ngspice .control block (run, then wrdata of the outputs).

    Returns
    -------
    Result
        text (the deck; the command writes it to a file and names that "deck" instead);
        automatic_choices; analysis; unknowns (name, vector, sign: where ngspice holds each
        unknown); outputs (probe, vector, unit, description); notes.
        result.to_frame("unknowns"), result.to_frame("outputs"): those tables.

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    return _result("netlist", _emnet.netlist(
        as_scene(scene)._handle, text(analysis, "analysis"), number(periods, "periods"),
        integer(points_per_period, "points_per_period"), number(rtol, "rtol"),
        flag(control, "control")))


def crosscheck(scene: SceneLike, analyses: str = "all", timeout: Number = 60.0) -> Result:
    """emnet against ngspice on the same network (as `emnet crosscheck`).

    ngspice runs in its own worker process.

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    analyses : str, default "all"
        Some of "op,ac,modal,tran", or "all".
    timeout : float, default 60
        The worker's time limit [s].

    Returns
    -------
    Result
        scene, automatic_choices, backend, status, pass (every difference within its tolerance);
        rows: analysis, quantity, largest_difference, where, tolerance, pass, basis; timings [s];
        notes; total_seconds [s].
        result.to_frame(): the rows.

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or scene key.
    NumericalError
        The analysis failed (the reason in the message).
    """
    # An installed package runs its own worker (emnet/bin); the module in build/python finds the
    # one the build made.
    worker = program("emnet-ngspice-worker") or ""
    return _result("crosscheck", _emnet.crosscheck(
        as_scene(scene)._handle, text(analyses, "analyses"), number(timeout, "timeout"), worker))
