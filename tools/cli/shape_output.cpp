// --shape (cli/shape_output.hpp).
#include "cli/shape_output.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>

#include "cli/option_names.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/units.hpp"
#include "emnet/report/shape_plot.hpp"

namespace emnet_cli {

namespace {

std::string extension_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

void add_shape_options(CLI::App* command, ShapeOptions& shape, const std::string& what) {
  command->add_option("--shape", shape.path,
                      "write the beam's deformed shape " + what +
                          ": .csv (x, y per node and instant), .png or .svg (the beam in the "
                          "plane at true aspect ratio, every instant coloured by its phase, the "
                          "undeformed beam faint) or .gif (an animation of one period); e.g. "
                          "--shape fin.gif");
  sets_fields(command->add_option("--shape-instants", shape.instants,
                                  "instants over one period for --shape (default 36 for a .gif, "
                                  "8 otherwise; from 2, at most 1000 frames in a .gif)"),
              {"shape_instants"});
}

int shape_instants(const ShapeOptions& shape) {
  if (shape.path.empty()) {
    if (shape.instants != 0)
      throw emnet::InputError("--shape-instants", "--shape",
                              "--shape-instants sets the instants of --shape: give --shape PATH");
    return 0;
  }
  const std::string extension = extension_of(shape.path);
  if (extension != ".csv" && extension != ".png" && extension != ".svg" && extension != ".gif")
    throw emnet::InputError(
        "--shape", "--shape",
        "'" + shown(shape.path) + "' must end in .csv, .png, .svg or .gif (an animation)");
  if (shape.instants != 0) return shape.instants;
  return extension == ".gif" ? 36 : 8;
}

void write_shape(const ShapeOptions& shape, const std::optional<emnet::DeformedShape>& result,
                 const emnet::Model& model, const std::string& what, const CommonOptions& options,
                 bool say) {
  if (shape.path.empty() || !result) return;
  const emnet::DeformedShape& drawn = *result;
  const std::string frequency = emnet::format_number("%.6g", drawn.frequency) + " Hz";
  if (extension_of(shape.path) == ".csv") {
    const size_t nodes = drawn.reference_x.size();
    write_csv_rows(shape.path, {"time_s", "node", "reference_x_m", "x_m", "y_m"},
                   drawn.times.size() * nodes, [&](size_t i, auto& row) {
                     const size_t t = i / nodes, k = i % nodes;
                     row.insert(row.end(), {drawn.times[t], static_cast<double>(k),
                                            drawn.reference_x[k], drawn.x[t][k], drawn.y[t][k]});
                   });
  } else {
    const bool large = model.scene.beam.kinematics == emnet::BeamKinematics::large;
    const std::string title = model.scene.name + ": " + what + " at " + frequency + ", " +
                              (large ? "large" : "small") + " kinematics";
    check_plot(emnet::write_shape_plot(shape.path, title, drawn, plot_output(options, false)));
  }
  if (say)
    std::cout << "shape written to " << shown(shape.path) << " (" << drawn.times.size()
              << " instants over one period at " << frequency << ")\n";
}

}  // namespace emnet_cli
