// The outputs a model offers beyond its scene's probes, each with a record of where it comes
// from: the speckle-point differences dx_k = P_k − P1 and the DEAs' electrical quantities.
//
// Speckle-point differences (the paper's Eqs. 20–22, its Fig. 12): with a probe named P1 (the
// reference speckle point, at the clamp on the fish fin), each other probe P_k of the same
// quantity (a name "P" followed by at least one character) gives dx_k = P_k − P1, named "dx"
// followed by what follows the "P" ("P4" → "dx4"), described as "P4 - P1": P1's terms
// subtracted from P_k's. DEA outputs: each DEA with an electrical model (drive.electrical_dynamics)
// gives its capacitor voltage u_X and its current i_X.
//
// Two output lists are built from these, one for each use:
//   transient_output_list  (emnet tran, sweep-switching, mismatch, identify --peak): the scene's
//     probes with each P_k replaced by its dx_k and P1 left out (whenever there is a P1: it is
//     the reference; on the fish fin it sits at the clamp and is identically zero, and dx_k is
//     what the paper measures), then the DEA outputs;
//   deck_output_list  (SPICE decks, spice_output_probes): the scene's probes as they are, P1
//     included (a deck's outputs are compared with emnet probe by probe, the raw P_k as well),
//     then every dx_k, then the DEA outputs; a probe a deck cannot carry is left out of it
//     (deck_exports), with a note (deck_left_out_notes) that the cross-check repeats.
// A deck writes an output as node voltages weighted by G sources: a probe whose terms name a
// branch unknown (reaction_force, reaction_moment, spring_force: an inductor's or a lever's
// current) or that has squares (dea_force, and a reaction moment with a DEA end on the held
// end) is not exported.
#pragma once

#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

/// Where a ModelOutput comes from.
enum class OutputOrigin {
  scene_probe,               ///< one of Model::probes
  speckle_point_difference,  ///< dx_k = P_k − P1
  dea_voltage,               ///< u_X: DEA X's capacitor voltage
  dea_current,               ///< i_X: the current into DEA X
};

/// One output of a model: a probe of its network and what it stands for.
struct ModelOutput {
  Probe probe;
  OutputOrigin origin = OutputOrigin::scene_probe;  ///< see OutputOrigin
  /// scene_probe: its index in Model::probes; speckle_point_difference: P_k's index there.
  int probe_index = -1;
  int reference_index = -1;  ///< speckle_point_difference: P1's index in Model::probes
  std::string dea;           ///< dea_voltage, dea_current: the DEA's name
};

/// The index of P1 in Model::probes (the last probe of that name); -1 when there is none.
int speckle_point_reference(const Model& model);
/// dx_k = P_k − P1 for every P_k of Model::probes, in their order; none without a P1.
std::vector<ModelOutput> speckle_point_differences(const Model& model);
/// u_X and i_X of every DEA with an electrical model, in DEA order (u before i).
std::vector<ModelOutput> dea_electrical_outputs(const Model& model);

/// The film voltage probe (dea_voltage:X) of each DEA a [[circuit]] drives (circuit_driven_deas,
/// in its order) that has its electrical model (an electrode node): what tran judges where the
/// circuit proves no bound, and what ac reads at the operating point.
struct CircuitDeaVoltageProbe {
  std::string dea;  ///< the DEA's name
  Probe probe;      ///< its dea_voltage probe
};
/// The CircuitDeaVoltageProbe of each such DEA of `model`.
std::vector<CircuitDeaVoltageProbe> circuit_dea_voltage_probes(const Model& model);

/// What tran (and sweep-switching, mismatch) show: the scene's probes, P_k replaced by dx_k, then
/// u_X, i_X of every DEA with an electrical model unless a scene probe shows that quantity
/// already. A deck's list: every probe a deck carries, the dx_k, then the same u_X, i_X.
std::vector<ModelOutput> transient_output_list(const Model& model);
/// The deck's list (see above).
std::vector<ModelOutput> deck_output_list(const Model& model);

/// The output a comparison of one deflection takes by default (mismatch, a sweep's resonance):
/// the last speckle-point difference of `outputs`, else their last deflection; nullptr when
/// they have no deflection.
const ModelOutput* default_deflection_output(const std::vector<ModelOutput>& outputs);

/// The probes of `outputs`, in their order.
std::vector<Probe> probes_of(const std::vector<ModelOutput>& outputs);

/// Whether a SPICE deck carries `probe` of `model` (see above); when not, why, in words.
bool deck_exports(const Model& model, const Probe& probe);
/// Why a SPICE deck does not carry `probe` of `model`, in words.
std::string deck_export_refusal(const Model& model, const Probe& probe);
/// "probe NAME (QUANTITY) is not exported to SPICE decks: WHY" for every scene probe left out.
std::vector<std::string> deck_left_out_notes(const Model& model);

}  // namespace emnet
