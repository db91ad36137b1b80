// JSON of a SPICE deck's map (emnet/spice/spice_netlist.hpp): where ngspice holds each of
// emnet's unknowns and outputs. `emnet netlist -o DECK --json` prints it after "deck" (the
// file), emnet.netlist returns it after "text" (the deck). Keys in this order:
// automatic_choices, analysis (op, ac or tran), unknowns [{name, vector, sign}] (one per unknown
// of the model's assembled network), outputs [{probe, vector, unit, description}], notes.
#pragma once

#include "emnet/model/model.hpp"
#include "emnet/report/json.hpp"
#include "emnet/spice/spice_netlist.hpp"

namespace emnet {

/// The JSON of a deck's map.
/// @param deck   the SpiceDeck of `write_spice_deck` on `model`
/// @param model  the model the deck was written from (its unknowns' names, automatic choices)
Json to_json(const SpiceDeck& deck, const Model& model);

}  // namespace emnet
