// What the model builder shares with the probes' file (src/model/probes.cpp), private to the
// model layer.
#pragma once

#include "emnet/model/model.hpp"

namespace emnet {

// The probe `spec` on `model`'s beam and DEAs; `dea` is the DEA an electrical probe names
// (nullptr when there is none of that name). Throws InputError as Model::make_probe.
Probe make_probe_on(const Model& model, const ProbeSpec& spec, const DeaLayout* dea);

}  // namespace emnet
