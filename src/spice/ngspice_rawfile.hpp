// The ngspice rawfile parser's private part: parse_ngspice_rawfile itself is public
// (emnet/spice/ngspice_runner.hpp); here the renaming of rawfile vector names to ngspice's own.
#pragma once

#include <string>

#include "emnet/spice/ngspice_runner.hpp"

namespace emnet {

// Rawfile names as ngspice names its vectors: "v(out)" -> "out", "i(v1)" -> "v1#branch";
// every other name in lower case.
std::string vector_name_from_rawfile(const std::string& rawfile_name);

}  // namespace emnet
