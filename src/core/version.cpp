// emnet::version(): EMNET_VERSION comes from CMake's project() version (cmake/version.h.in).
#include "emnet/core/version.hpp"

#include "emnet_version.h"

namespace emnet {

const char* version() {
  return EMNET_VERSION;
}

}  // namespace emnet
