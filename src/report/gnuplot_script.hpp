// Writing and running a gnuplot script for one image (src/report, private to the report layer):
// the image's file names, text and numbers as gnuplot reads them, and a run of gnuplot that
// leaves a complete image or the previous one. plot.cpp draws its plots through it.
#pragma once

#include <filesystem>
#include <functional>
#include <sstream>
#include <string>

#include "emnet/core/errors.hpp"
#include "emnet/report/plot.hpp"

namespace emnet::gnuplot {

enum class ImageFormat { png, svg, gif };

// The image's directory and the names of the image, its data and its script.
struct PlotFiles {
  ImageFormat format = ImageFormat::png;
  std::filesystem::path directory;  // where gnuplot runs; "." for a bare file name
  std::string image_name;           // file names relative to `directory`
  std::string data_name;
  std::string script_name;
  std::string data_path;  // full paths, for messages
  std::string script_path;
  std::string image_path;
};

// Splits the image path into directory and file names; fails on an unknown extension (".gif",
// an animation, only where `animation` allows it).
Status plot_files_for(const std::string& image_path, PlotFiles& files, bool animation = false);

// `text` on one line: each control character (newline, tab, ...) becomes a space.
std::string one_line(const std::string& text);
// `text` as a single-quoted gnuplot string: one line, each quote doubled. gnuplot expands
// neither backslashes, backquotes nor '@' macros inside single quotes.
std::string gnuplot_string(const std::string& text);
// A number as gnuplot reads it, independent of the global locale; NaN for a missing point.
std::string number_text(double value);
// A text stream for a data file or script, in the classic locale.
std::ostringstream classic_stream();

// Terminal line of a script; `height` in pixels. The output line follows it (`set output`).
// A GIF is animated, each plot command a frame shown for `frame_delay` hundredths of a second.
std::string gnuplot_terminal_line(const PlotFiles& files, int width, int height,
                                  int frame_delay = 10);
// The comment that opens a saved script: what it draws, its data, how to re-draw.
std::string script_header(const PlotFiles& files, const std::string& what,
                          const std::string& title);

// The script's body for a data file name (the saved data beside the image, or its hidden copy).
using ScriptBody = std::function<std::string(const std::string& data_name)>;

// Draws `preamble`, the output line and `body` over `data` in a private temporary directory
// beside the image and renames the drawing onto `image_path`; then, with
// `output.data_and_script`, writes the data and the script (reading the data beside it) beside
// the image. Cancelled through `output.progress`: no file written, cancelled_status().
Status write_script_and_run(const PlotFiles& files, const std::string& preamble,
                            const ScriptBody& body, const std::string& data,
                            const std::string& image_path, const PlotOutput& output);

}  // namespace emnet::gnuplot
