// How the switching sweep chooses its method and prepares the model it sweeps (the automatic
// choice of emnet/studies/switching_sweep.hpp), shared by the sweep's run and
// prepare_swept_model.
#pragma once

#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"

namespace emnet {

// The swept model's PrepareOptions: `given`, with large kinematics served (by shooting) unless
// the method is the exact one (then "auto" stays small; an explicit "large" is refused).
PrepareOptions served_by_the_sweep(const Scene& scene, PrepareOptions given,
                                   SwitchingSweepMethod method = SwitchingSweepMethod::automatic);

// `given` with SwitchingSweepMethod::automatic replaced by what it chooses (the header), the
// reason in `notes`; an exact cascade's solver made here (options.solver), its time added to
// `decomposition_seconds`.
SwitchingSweepOptions resolve_sweep_method(const Model& model, const SwitchingSweepOptions& given,
                                           std::vector<std::string>& notes,
                                           double& decomposition_seconds);

}  // namespace emnet
