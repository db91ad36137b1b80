// Cross-check against ngspice: the scene's network exported as SPICE decks
// (spice_netlist.hpp), run by ngspice (ngspice_runner.hpp), its vectors mapped back to emnet's
// unknowns and probes (emnet value = sign × vector) and compared with emnet's own analyses.
//
// What is compared, and the tolerance each is held to:
//
//  * op: every unknown the op deck has a vector for (displacements, rotations, voltages,
//    lever forces) against solve_static's state z, and every output probe against
//    static_probe_value. A difference is relative to the largest magnitude of its group (the
//    unknowns of one kind and domain, or the probes of one unit), so that a node near the clamp
//    or a quantity that is zero at rest is not divided by its own small value. A group that is
//    zero in emnet (the DEA currents at rest, the clamp probe P1) is held to the tolerance times
//    1 SI unit, i.e. an absolute 1e-6 A / m. Tolerance 1e-6: the same linear(ised) equations
//    solved by LU in double precision on both sides; the deck carries 12 significant digits, so
//    rounding gives ~1e-12 times the network's condition. ngspice's Newton test on the op
//    (reltol 1e-9 in the op deck) stops far below that. Any wrong weight, sign or element value
//    shows at the percent level.
//  * ac: every output probe, magnitude and phase, at every frequency of ngspice's own frequency
//    vector (emnet evaluated at exactly those frequencies). Magnitude: ||Y_s| − |Y_e|| / peak
//    (peak: the largest |Y_e| of that output over the sweep). Phase: |arg(Y_s / Y_e)| ·
//    |Y_e| / peak [rad], the phase difference weighted by the relative magnitude, since a
//    phase is undefined where the response vanishes. Also every unknown with a vector
//    (velocities, angular velocities, voltages, branch currents) as the complex difference
//    relative to the largest magnitude of its group over the sweep. Integrator outputs
//    (deflections) are skipped at f = 0: the deck's integrator (1 F ‖ 1 GΩ) gives 0 there, where
//    emnet gives the static limit. The integrator's leak makes the deck's deflection
//    1/(1 + 1/(jω·1e9 s)), a relative difference of 1.6e-9 at 0.1 Hz, far below the tolerance.
//    Tolerance 1e-6, as for op (same network, different arithmetic).
//  * modal: emnet's first modes (run_modes) against the peaks of ngspice's AC response of one
//    deflection output (the probe "tip", else the last deflection probe). Each peak comes from a
//    dedicated ac deck with 200 points over ±1 % around the mode's amplitude peak
//    f_p = f_n·sqrt(1 − 2ζ²) (f_n natural frequency, ζ damping ratio of the pole), located by a
//    parabola through 1/|H|² against f² at the three grid points around the largest |H|. For an
//    isolated mode of a displacement output 1/|H|² is exactly quadratic in ω² (viscous or
//    Kelvin–Voigt damping alike) with its minimum at f_p, so the fit has no grid error of its
//    own; what remains is the shift caused by the other modes' background. That shift is
//    measured on emnet's own AC response, evaluated on the same grid and fitted the same way,
//    and the tolerance is that shift plus 1e-6·f_p: ngspice must find the mode where emnet's
//    own response puts it, to the AC check's 1e-6. A mode whose peak is not inside the fine grid
//    (e.g. a node of the mode shape at the probe) is reported as not visible and not compared.
//  * tran: emnet's exact method (matrix exponentials; rounding only, run_transient_exact)
//    evaluated at ngspice's own time points (at most 2000 of them, evenly strided), against
//    ngspice with `.options reltol` 1e-6, vntol 1e-12, abstol 1e-15 and max step = period /
//    2000 (period: the shorter of the drive's and the first mode's; the first mode's without a
//    drive frequency), over 2 periods of the drive (or of the first mode) from rest. The exact
//    method needs a linear network: a scene whose DEAs have their electrical model (RC loop, force
//    on the capacitor voltage) is checked with the ideal drive (drive.electrical_dynamics = false,
//    force k_F·V(t)² from the source), said in a note; a network that is still nonlinear uses IDA
//    at rtol 1e-10 as the reference (at 1e-9 or 1e-8 where rounding stops IDA's corrector at 1e-10,
//    said in the note). The deck switches with linear edges of width ε centred on emnet's instants
//    (ε = 1e-5 × the shorter level time); points within ±10ε of an edge are excluded (stated).
//    Outside, the edge's effect is a zero-mean pulse, of second order: ~(ε·2π·f)² relative, 1e-9 at
//    40 Hz for ε = 1 µs. The difference is relative to each output's peak |value| over the run: it
//    is ngspice's error against the exact solution. Tolerance: 100 × reltol. ngspice's trapezoidal
//    rule keeps its local truncation error near trtol (7) × reltol; the global error of an undamped
//    or lightly damped oscillation accumulates as phase error, and where the max step is
//    coarse it dominates. Measured (2026-11-22): fish fin 1.5e-5 at max step T/2000 (3.7e-4 at
//    T/200, 4.8e-5 at T/1000, 5.2e-6 at T/4000: the max step's part, ∝ h^1.5); cantilever
//    3.1e-5 (its step load excites every mode, ngspice's steps are ~4 µs whatever the max
//    step: reltol's part). 100 × reltol = 1e-4 holds both with a margin of 3 and still catches a
//    wrong element or sign (≥ 1e-2). ngspice's error is not proportional to reltol (cantilever:
//    8.6e-5 at reltol 1e-5), so other --reltol values keep the multiple without a measurement.
//
// With beam.kinematics = "large" every analysis is compared (the chords' changes and angles in
// groups of their own): the ac deck is then written in displacements, so that ngspice linearises
// about the deflected static state (include/emnet/spice/spice_netlist.hpp), and its integral
// outputs are compared at f = 0 too.
//
// Wall times: ngspice's (loading and running the deck and reading the vectors back,
// NgspiceResult::ngspice_seconds) and emnet's analysis of the same question, measured in the
// same run.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/model/model.hpp"
#include "emnet/spice/ngspice_runner.hpp"

namespace emnet {

enum class CrosscheckAnalysis { op, ac, modal, tran };
const char* crosscheck_analysis_name(CrosscheckAnalysis analysis);
// "op,ac,modal,tran" or "all"; throws OptionError (the field "analyses") on an unknown name.
std::vector<CrosscheckAnalysis> parse_crosscheck_analyses(const std::string& text);

struct CrosscheckOptions {
  std::vector<CrosscheckAnalysis> analyses = {CrosscheckAnalysis::op, CrosscheckAnalysis::ac,
                                              CrosscheckAnalysis::modal, CrosscheckAnalysis::tran};
  NgspiceOptions ngspice;
  // op and ac (and the modal check's arithmetic part): same network, different arithmetic.
  double same_network_tolerance = 1e-6;
  // modal: how many oscillatory modes, lowest first (f1, f2 when visible).
  int modal_count = 2;
  double modal_half_width = 0.01;  // fine grid: f_p·(1 ± this)
  int modal_points = 200;          // even, so that f_p falls between two grid points
  // tran: end time = tran_periods × the drive's period (a scene with a [[circuit]] and drive
  // kind none: that of drive.frequency, when given; without a drive frequency, the first
  // mode's period); output step = period / tran_points_per_period.
  double tran_periods = 2.0;
  int tran_points_per_period = 2000;  // also ngspice's max step: period / this
  // ngspice's time points compared: at most this many, evenly strided (emnet's exact method
  // costs one matrix exponential per distinct step; a stiff deck takes ~1e5 points).
  std::size_t tran_compared_points = 2000;
  double tran_reltol = 1e-6;
  double tran_edge_fraction = 1e-5;
  double tran_edge_exclusion = 10.0;  // excluded window: ± this × ε around every edge
  // tolerance = this × reltol × peak (measured: see docs/commands.md, "Cross-check").
  double tran_tolerance_per_reltol = 100.0;
  // Decks are written here too when not empty (<scene>-crosscheck-<analysis>.cir).
  std::string keep_decks_directory;
  std::vector<std::string> overrides;  // listed in the decks' headers
  // Called with every ngspice result before it is compared (tests perturb vectors with it).
  std::function<void(CrosscheckAnalysis, NgspiceResult&)> inspect_ngspice_result;

  /// The checks of the options alone, as run_crosscheck makes them first.
  /// @throws OptionError naming the field out of its range ("tran_periods", "modal_count", ...)
  void validate() const;
};

struct CrosscheckRow {
  CrosscheckAnalysis analysis = CrosscheckAnalysis::op;
  std::string quantity;           // "displacements (translational)", "P4 |Y|", "f1 [Hz]", …
  double largest_difference = 0;  // relative (see the header comment)
  std::string where;              // node, frequency or time of the largest difference
  double tolerance = 0;
  bool pass = true;
  std::string basis;  // what the difference is relative to
};

struct CrosscheckTiming {
  CrosscheckAnalysis analysis = CrosscheckAnalysis::op;
  double ngspice_seconds = 0;        // ngspice's part (load, run, read back)
  double ngspice_total_seconds = 0;  // including the worker or program start
  double emnet_seconds = 0;          // emnet's analysis of the same question
  std::string emnet_what;            // "solve_static", "run_ac at 1000 frequencies", …
};

struct CrosscheckReport {
  Status status;  // failure: ngspice missing / failing / timed out, or an emnet analysis failed
  std::string backend;  // NgspiceResult::backend_description of the runs
  std::vector<CrosscheckRow> rows;
  std::vector<CrosscheckTiming> timings;
  std::vector<std::string> notes;
  bool all_pass() const;
};

// Runs the cross-check. Throws OptionError for options out of range (CrosscheckOptions::validate)
// or a keep_decks_directory that cannot be written, InputError for a model the deck writer
// refuses; ngspice's and emnet's failures are a failing status.
CrosscheckReport run_crosscheck(const Model& model, const CrosscheckOptions& options = {});

// ---- the comparison, for reuse and tests -------------------------------------------------
// Largest of |a_k − b_k| / scale over k with the index where it occurs; scale ≤ 0 uses 1.
struct LargestDifference {
  double value = 0;
  std::size_t index = 0;
};
LargestDifference largest_relative_difference(const std::vector<double>& a,
                                              const std::vector<double>& b, double scale);

// Peak location of |H| sampled on an increasing grid: parabola through 1/|H|² against f² at
// the three points around the largest |H| (exact for an isolated mode of a displacement
// output). False when the largest |H| is at an end of the grid or the fit has no minimum.
bool parabolic_peak_frequency(const std::vector<double>& frequencies,
                              const std::vector<double>& magnitudes, double& peak_hz);

}  // namespace emnet
