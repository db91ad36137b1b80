// The version of emnet: the one in CMakeLists.txt's project(), compiled into the library, which
// the command line (emnet --version) and the Python package (emnet.__version__, and its wheel's
// metadata, read from the same line) report.
#pragma once

namespace emnet {

/// The version as MAJOR.MINOR.PATCH ("0.1.0").
const char* version();

}  // namespace emnet
