// JSON of a SPICE deck's map (emnet/report/spice_deck_json.hpp).
#include "emnet/report/spice_deck_json.hpp"

namespace emnet {

Json to_json(const SpiceDeck& deck, const Model& model) {
  const System system = model.network.assemble();
  Json out;
  out["automatic_choices"] = to_json(model.automatic_choices);
  out["analysis"] = spice_analysis_name(deck.analysis);
  out["unknowns"] = Json::array();
  for (size_t k = 0; k < deck.unknowns.size(); ++k)
    out["unknowns"].push_back({{"name", system.unknowns[k].name},
                               {"vector", deck.unknowns[k].vector},
                               {"sign", deck.unknowns[k].sign}});
  out["outputs"] = Json::array();
  for (const auto& output : deck.outputs)
    out["outputs"].push_back({{"probe", output.probe},
                              {"vector", output.vector},
                              {"unit", output.unit},
                              {"description", output.description}});
  out["notes"] = deck.notes;
  return out;
}

}  // namespace emnet
