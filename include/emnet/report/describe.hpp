// A scene's drive in words, for the lines every result prints: the header's drive summary and,
// with every AC result, what the AC input is (which part of the drive, linearised how, and the
// DEAs' RC factor the square-wave drives leave out of it). Text from the scene (DEA names) is
// shown as on a terminal (emnet/core/terminal_text.hpp).
#pragma once

#include <string>

#include "emnet/scene/scene.hpp"

namespace emnet {

/// "drive antagonistic 0/3000 V square wave at 6 Hz", "drive single V0 + v*sin(...) ...",
/// "drive none, circuit source(s) amp" (a circuit's sources named after the drive kind).
std::string drive_summary(const Scene& scene);

/// What the AC input is, in words. `top_hz`: the sweep's highest frequency [Hz], where the
/// square-wave drives' omitted RC factor 1/(1 + j·2π·f·τ) is largest (τ: drive_time_constant).
std::string ac_input_description(const Scene& scene, double top_hz);

/// The AC input in a few words, for a plot's title: "the antagonistic drive's force level
/// k_F*V^2/2 as a sinusoid (V = 4000 V, DEAs A and B in antiphase)", "ac 1 V of circuit source
/// amp"; empty when nothing is driven.
std::string ac_input_summary(const Scene& scene);

}  // namespace emnet
