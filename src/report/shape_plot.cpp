// The beam's deformed shape as a picture or an animation (emnet/report/shape_plot.hpp).
#include "emnet/report/shape_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gnuplot_script.hpp"

namespace emnet {

namespace {

using gnuplot::classic_stream;
using gnuplot::gnuplot_string;
using gnuplot::number_text;

constexpr int kShapeWidthPx = 1000;

// The plotted range [mm], padded by 5 % of the larger span, and the image's height for a true
// aspect ratio at kShapeWidthPx (room for the title, the labels and the colour bar).
struct ShapeFrame {
  double x_lo = 0, x_hi = 1, y_lo = -1, y_hi = 1;
  int height_px = 400;
};

ShapeFrame shape_frame(const DeformedShape& shape) {
  ShapeFrame frame;
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;
  bool any = false;
  auto take = [&](double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x_lo = any ? std::min(x_lo, x) : x;
    x_hi = any ? std::max(x_hi, x) : x;
    y_lo = any ? std::min(y_lo, y) : y;
    y_hi = any ? std::max(y_hi, y) : y;
    any = true;
  };
  for (double x : shape.reference_x) take(1e3 * x, 0.0);
  for (size_t t = 0; t < shape.x.size(); ++t)
    for (size_t k = 0; k < shape.x[t].size(); ++k) take(1e3 * shape.x[t][k], 1e3 * shape.y[t][k]);
  const double span = std::max({x_hi - x_lo, y_hi - y_lo, 1e-9});
  frame.x_lo = x_lo - 0.05 * span;
  frame.x_hi = x_hi + 0.05 * span;
  frame.y_lo = y_lo - 0.05 * span;
  frame.y_hi = y_hi + 0.05 * span;
  const double plot_width = kShapeWidthPx - 200.0;  // left label, colour bar
  const double ratio = (frame.y_hi - frame.y_lo) / (frame.x_hi - frame.x_lo);
  frame.height_px = static_cast<int>(std::clamp(plot_width * ratio + 160.0, 260.0, 1000.0));
  return frame;
}

// Each instant's phase: t/T modulo 1 over a period, or t over the last instant of a transient.
double phase_of(const DeformedShape& shape, size_t t) {
  if (shape.period() > 0.0) return std::fmod(shape.times[t] / shape.period(), 1.0);
  return shape.times.back() > 0.0 ? shape.times[t] / shape.times.back() : 0.0;
}

// Block 0 the undeformed beam, block 1 + t the instant t: x [mm], y [mm], phase.
std::string shape_data(const DeformedShape& shape) {
  std::ostringstream data = classic_stream();
  data << "# undeformed beam: x [mm], y [mm]\n";
  for (double x : shape.reference_x) data << number_text(1e3 * x) << " 0 0\n";
  for (size_t t = 0; t < shape.times.size(); ++t) {
    data << "\n\n# t = " << number_text(shape.times[t]) << " s: x [mm], y [mm], phase\n";
    for (size_t k = 0; k < shape.x[t].size(); ++k)
      data << number_text(1e3 * shape.x[t][k]) << " " << number_text(1e3 * shape.y[t][k]) << " "
           << number_text(phase_of(shape, t)) << "\n";
  }
  return data.str();
}

std::string frame_settings(const ShapeFrame& frame, const std::string& title, bool periodic) {
  std::ostringstream script = classic_stream();
  script << "set title " << gnuplot_string(title) << " noenhanced\n"
         << "set size ratio -1\nset grid\nset key top left opaque\n"
         << "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
         << "set xrange [" << number_text(frame.x_lo) << ":" << number_text(frame.x_hi) << "]\n"
         << "set yrange [" << number_text(frame.y_lo) << ":" << number_text(frame.y_hi) << "]\n"
         << "set palette model HSV defined (0 0 0.85 0.8, 1 1 0.85 0.8)\n"
         << "set cbrange [0:1]\nset cblabel " << (periodic ? "'t / T'" : "'t / t_end'")
         << " noenhanced\n";
  return script.str();
}

std::string undeformed(const std::string& data_name) {
  return gnuplot_string(data_name) +
         " index 0 using 1:2 with lines lw 5 lc rgb '#d8d8d8' title 'undeformed'";
}

// Every instant in one picture.
std::string picture_body(const std::string& data_name, const DeformedShape& shape) {
  std::ostringstream script = classic_stream();
  script << "plot " << undeformed(data_name) << ", \\\n     for [i=1:" << shape.times.size() << "] "
         << gnuplot_string(data_name)
         << " index i using 1:2:3 with lines lw 2 lc palette notitle\n";
  return script.str();
}

// One frame per instant, its time in the title.
std::string animation_body(const std::string& data_name, const DeformedShape& shape,
                           const std::string& title) {
  std::ostringstream script = classic_stream();
  script << "unset colorbox\n";
  for (size_t t = 0; t < shape.times.size(); ++t) {
    std::ostringstream when = classic_stream();
    when << title << ", t = " << number_text(shape.times[t]) << " s";
    if (shape.period() > 0.0) when << " (" << number_text(phase_of(shape, t)) << " T)";
    script << "set title " << gnuplot_string(when.str()) << " noenhanced\n"
           << "plot " << undeformed(data_name) << ", " << gnuplot_string(data_name) << " index "
           << t + 1 << " using 1:2:3 with lines lw 3 lc palette notitle\n";
  }
  return script.str();
}

Status check_shape(const std::string& path, const DeformedShape& shape, bool animation) {
  if (shape.times.empty() || shape.reference_x.empty())
    return Status::failure("shape plot '" + path + "': no instant or no node to draw");
  if (shape.x.size() != shape.times.size() || shape.y.size() != shape.times.size())
    return Status::failure("shape plot '" + path + "': one curve per instant expected");
  for (size_t t = 0; t < shape.times.size(); ++t)
    if (shape.x[t].size() != shape.reference_x.size() ||
        shape.y[t].size() != shape.reference_x.size())
      return Status::failure("shape plot '" + path + "': one point per node expected");
  if (animation && shape.times.size() > static_cast<size_t>(kShapeAnimationFrames))
    return Status::failure("shape animation '" + path + "': " + std::to_string(shape.times.size()) +
                           " instants, at most " + std::to_string(kShapeAnimationFrames) +
                           " frames are drawn");
  return Status::success();
}

}  // namespace

Status write_shape_plot(const std::string& path, const std::string& title,
                        const DeformedShape& shape, const PlotOutput& output) {
  gnuplot::PlotFiles files;
  if (Status status = gnuplot::plot_files_for(path, files, true); !status.ok()) return status;
  const bool animation = files.format == gnuplot::ImageFormat::gif;
  if (Status status = check_shape(path, shape, animation); !status.ok()) return status;
  const ShapeFrame frame = shape_frame(shape);
  // One period in about two seconds (GIF delays are hundredths of a second, at least 2).
  const int delay = std::max(2, static_cast<int>(200 / shape.times.size()));
  const std::string preamble =
      gnuplot::script_header(files, animation ? "Shape animation" : "Shape plot", title) +
      gnuplot::gnuplot_terminal_line(files, kShapeWidthPx, frame.height_px, delay);
  const gnuplot::ScriptBody body = [&](const std::string& data_name) {
    return frame_settings(frame, title, shape.period() > 0.0) +
           (animation ? animation_body(data_name, shape, title) : picture_body(data_name, shape));
  };
  return gnuplot::write_script_and_run(files, preamble, body, shape_data(shape), path, output);
}

}  // namespace emnet
