// What the scene's drive applies to each DEA, and the excitation it gives a model's network.
//
// Drives (dea_drive), per DEA named by drive.deas:
//   antagonistic       A: 0/V square wave on for the first `duty` of each period, B the rest;
//                      A's on-time lengthened by `overlap` (both on together; < 0: a dead time).
//                      Static / at rest: A on (the sources at t = 0).
//   switched           one DEA: 0/V square wave on for the first `duty` of each period (how a
//                      unimorph is driven). Static / at rest: on.
//   bias_differential  V_A = V₀ + v·sin(2πft), V_B = V₀ − v·sin(2πft); AC input: v on A, −v on
//                      B, the network linearised at V₀ (moment exactly linear in v).
//   single             V = V₀ + v·sin(2πft) on one DEA; AC input v, linearised at V₀.
// A DEA the drive does not name gets the constant 0 V (the model builder adds no source at all
// on a DEA that a [[circuit]] element drives: emnet/model/circuit.hpp).
//
// AC input of the square-wave drives. A voltage switched between 0 and V is two-level, so its
// square is V times itself: the force k_F·V(t)² = k_F·V·V(t) is exactly a 0/k_F·V² square wave,
// linear in the switching function, with no linearisation about an operating voltage (which
// at 0 V would give no force and at V twice the swing). Its alternating part, ±k_F·V²/2 about
// the mean k_F·V²/2, is the AC input (one sinusoid of amplitude k_F·V²/2 per DEA; A and B in
// antiphase for the antagonistic pair, whose means cancel); the response to the square wave's
// fundamental is 4/π times the AC result. The input is this force applied directly, not
// through the RC loops, whatever drive.electrical_dynamics: through a loop the capacitor
// voltage is a first-order lag, and the force's fundamental is the same times 1/(1 + jωτ)
// (exactly at duty 0.5 for τ ≪ T: the square of the lagged wave differs from V times it only
// by equal pulses at both edges, which repeat every half period and have no fundamental); the
// AC result leaves this factor out, (ωτ)²/2 in amplitude and ωτ in phase. The network is
// linearised at the static state (the sources at t = 0), which matters only to the
// back-coupling gyrator K = 2·k_F·U₀ of a DEA that asks for it.
//
// Drive sources (Component::drive_source in emnet/model/structure.hpp): with
// drive.electrical_dynamics, DEA X's source voltage V(t) behind its RC loop; without, its force
// F(t) = k_F·V(t)² entered directly as current sources along its coupling nodes, one per part
// of the squared waveform (squared_force) and coupling node.
#pragma once

#include <string>
#include <vector>

#include "emnet/model/structure.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/waveform.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

struct DeaLayout;
struct Model;

/// What a drive applies to DEA `dea_name`: its source voltage (constant 0 for a DEA the drive
/// does not name) and, for the square-wave drives, the factor f of its AC force input f·k_F·V²
/// (±1/2; 0 for the sine drives, whose AC input is the source's own amplitude v).
struct DeaDrive {
  Waveform voltage;              ///< the source voltage [V]
  double ac_force_factor = 0.0;  ///< f
};
/// The DeaDrive of DEA `dea_name` under `drive`.
DeaDrive dea_drive(const DriveSpec& drive, const std::string& dea_name);

/// F(t) = k_F·V(t)² for a source waveform V, as waveforms: a pulse stays a pulse (0/V → 0/k_F·V²
/// when its low level is 0); V0 + v·sin(ωt) squares to k_F·(V0² + v²/2) + 2k_F·V0·v·sin(ωt)
/// − k_F·(v²/2)·cos(2ωt). The first waveform carries the AC input: `ac_force` for the
/// square-wave drives, the linearisation 2k_F·V0·v for sine drives.
/// @param force_constant  k_F [N/V²]
/// @param ac_force        the AC force input of the square-wave drives [N]
std::vector<Waveform> squared_force(const Waveform& voltage, double force_constant,
                                    double ac_force);

/// The AC force amplitude f·k_F·V² of DEA `dea` under `drive` (dea_drive's factor).
double dea_ac_force(const DriveSpec& drive, const DeaLayout& dea);

/// The waveform of the drive source `record` (Component::drive_source) of DEA `dea` under
/// `drive`: its source voltage, or the part record.force_part of k_F·V(t)² times the coupling
/// coefficient record.coupling. The model builder makes its drive sources with this, and
/// drive_excitation remakes them with it.
/// @throws std::logic_error when `record` is not a drive source of `dea`
Waveform drive_source_waveform(const DriveSpec& drive, const DeaLayout& dea,
                               const ElementRecord& record);

/// The excitation of `model`'s network (assembled as `assembled`, model.network.assemble() or
/// assemble_excitation()) with the drive switched at `frequency` [Hz] instead of
/// drive.frequency: every drive source's waveform made again at that frequency, everything else
/// (loads, the DEAs' direct AC force, every source term) as assembled. It equals, bit for bit,
/// the excitation of a model built from the scene with drive.frequency = frequency (the same
/// waveforms from drive_source_waveform, the same stamps): nothing else of a resolved model
/// depends on drive.frequency (the loss factor has its own frequency, the fluid loading its
/// resonance, N and the RC dynamics are resolved).
/// @throws std::logic_error for a model whose drive sources do not each own exactly one waveform
///         of `assembled` (an excitation of another network)
Excitation drive_excitation(const Model& model, const Excitation& assembled, double frequency);

/// `assembled` with the waveform of every [[circuit]] source that `model` stamped made again
/// from `scene`'s entry (circuit_waveform): after set_switching_frequency on the scene the model
/// was prepared from, the same b(t) as a model prepared from it, at the cost of the waveforms
/// alone. Nothing else of a resolved model depends on a source's waveform.
/// @throws std::logic_error for an excitation that does not say which element stamped each
///         waveform, or a circuit entry that `scene` does not have (another scene)
Excitation circuit_excitation(const Model& model, const Scene& scene, const Excitation& assembled);

/// The largest RC time constant R_e·C₀ [s] of the DEAs the drive names (0 when it names none);
/// `which`, when given, receives that DEA's name.
double drive_time_constant(const Scene& scene, std::string* which = nullptr);

/// The scene's periodic [[circuit]] sources: square and sine (frequency > 0) and pulse with a
/// period > 0. With `names` empty every one of them, else exactly those named (circuit[].name);
/// indices into scene.circuit.
/// @throws InputError naming the scene file and "circuit" for a name that is not a circuit source
///         or whose waveform is not periodic
std::vector<size_t> switched_sources(const Scene& scene, const std::vector<std::string>& names);

/// Sets the switching frequency of `scene` to `frequency_hz` [Hz], the one home of this for
/// the switching sweep, the design study's sweep and the transient's `switching_hz`:
/// drive.frequency (the [drive]'s square wave, and the period of a transient), and the
/// frequency of every source switched_sources(scene, sources) gives, all to the same F
/// (sources of different frequencies included). Each source keeps its levels (low > high, an
/// inverted source, included), duty, rise and fall [s] and sine phase; a pulse's period becomes
/// 1/F and its width keeps its fraction of the period; the delay keeps its fraction of the
/// period (a phase-shifted pair stays shifted by the same phase). Returns notes for the
/// sources left as they are (dc, pwl, a single pulse) and for sources whose own frequencies
/// differed.
/// @throws InputError (scene file, the circuit or drive key) when nothing switches (a
///         [[circuit]] without a periodic source and drive.kind = "none"), or when a source's
///         rise and fall (and a pulse's width) no longer fit in the period 1/F
std::vector<std::string> set_switching_frequency(Scene& scene, double frequency_hz,
                                                 const std::vector<std::string>& sources = {});

/// drive.overlap is in seconds: DEA A's on-time duty·T + overlap must stay inside the period
/// (less the rise time at both edges) at the switching frequency `frequency_hz` too.
/// @throws OptionError naming the scene file and drive.overlap, and `field` (the Options field
///         that asked for the frequency: a sweep's "to"), when it does not
void check_overlap_fits(const Scene& scene, double frequency_hz, const std::string& field);

}  // namespace emnet
