// A scene's model, System and operating point (emnet/studies/prepared_model.hpp).
#include "emnet/studies/prepared_model.hpp"

#include <utility>

namespace emnet {

PreparedModel prepare_at_rest(const Scene& scene, const PrepareOptions& options,
                              const OperatingPointOptions& point_options) {
  PreparedModel prepared{{}, prepare_model(scene, options), {}, {}};
  prepared.system = prepared.model.network.assemble();
  OperatingPoint point = operating_point(prepared.system, point_options);
  prepared.status = point.status;
  if (point.about_zero) prepared.model.notes.push_back(point.note);
  prepared.rest = std::move(point.rest);
  return prepared;
}

}  // namespace emnet
