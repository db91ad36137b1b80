// A picture or an animation of the beam's deformed shape (emnet/model/deformed_shape.hpp)
// through gnuplot, as the other plots (emnet/report/plot.hpp: files written whole or not at all,
// gnuplot in a private directory under a time limit, every failure a Status).
//
// The beam in the plane at true aspect ratio, in millimetres: the undeformed beam in faint grey
// and the shape at each instant, coloured by its phase t/T over the period (a transient: t over
// its last instant) with the colour bar for a key. PNG or SVG: every instant in one picture. GIF:
// an animation, one frame per instant (at most kShapeAnimationFrames), each with the undeformed
// beam and the instant's time in its title; one period lasts about two seconds.
#pragma once

#include <string>

#include "emnet/core/errors.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/report/plot.hpp"

namespace emnet {

/// The most frames an animated GIF of a shape is drawn with (each is a plot of its own).
inline constexpr int kShapeAnimationFrames = 1000;

/// Writes `shape` to `path` (.png, .svg or .gif, by the extension).
/// @param title  the picture's title, shown as given
/// @return a failed Status for a wrong extension, an empty shape, more than
///         kShapeAnimationFrames instants in a GIF, or any failure of gnuplot or the files
Status write_shape_plot(const std::string& path, const std::string& title,
                        const DeformedShape& shape, const PlotOutput& output = {});

}  // namespace emnet
