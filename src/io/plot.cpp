// Plot writer: data file + gnuplot script + image; see include/emnet/plot.hpp.
#include "emnet/plot.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace emnet {

namespace {

constexpr double pi = 3.14159265358979323846;

// A label as a gnuplot string literal: one line, quotes and backslashes escaped.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\n' || c == '\r') c = ' ';
    if (c == '"' || c == '\\') out += '\\';
    if (c == '@' || c == '^' || c == '_' || c == '&' || c == '{' || c == '}') out += "\\\\";
    out += c;
  }
  return out + "\"";
}

std::string terminal_for(const std::string& path, int width, int height) {
  const bool svg = path.size() > 4 && path.substr(path.size() - 4) == ".svg";
  std::ostringstream out;
  if (svg)
    out << "set terminal svg size " << width << "," << height << " dynamic font 'Sans,12'\n";
  else
    out << "set terminal pngcairo size " << width << "," << height << " font 'Sans,11'\n";
  out << "set output " << quoted(path) << "\n";
  return out.str();
}

Status run_gnuplot(const std::string& script_path, const std::string& image_path) {
  const std::string command = "timeout 60 gnuplot " + quoted(script_path) + " >/dev/null 2>&1";
  const int code = std::system(command.c_str());
  if (code != 0) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
      return Status::failure(
          "gnuplot is not installed (Debian package gnuplot-nox); the data "
          "and script are in " +
          script_path);
    return Status::failure("gnuplot failed on " + script_path + " (exit " + std::to_string(code) +
                           ")");
  }
  std::ifstream image(image_path);
  if (!image) return Status::failure("gnuplot did not write " + image_path);
  return Status::success();
}

std::string marker_lines(const std::vector<PlotMarker>& markers, const char* yfrom) {
  std::ostringstream out;
  int index = 1;
  for (const auto& m : markers) {
    out << "set arrow " << index << " from " << m.frequency_hz << ", graph 0 to " << m.frequency_hz
        << ", graph 1 nohead dt 2 lc rgb '#aa0000'\n";
    out << "set label " << index << " " << quoted(m.label) << " at " << m.frequency_hz << ", "
        << yfrom << " offset 0.5,0 tc rgb '#aa0000'\n";
    ++index;
  }
  return out.str();
}

}  // namespace

Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency) {
  const std::string data_path = path + ".dat", script_path = path + ".gp";
  {
    std::ofstream data(data_path);
    if (!data) return Status::failure("cannot write " + data_path);
    data.precision(10);
    std::vector<double> previous_phase(series.size(), 0.0), offset(series.size(), 0.0);
    data << "# frequency_hz";
    for (const auto& s : series) data << "  |" << s.label << "| [" << s.unit << "]  phase [deg]";
    data << "\n";
    for (size_t f = 0; f < frequencies_hz.size(); ++f) {
      data << frequencies_hz[f];
      for (size_t k = 0; k < series.size(); ++k) {
        const auto v = f < series[k].values.size() ? series[k].values[f] : 0.0;
        const double magnitude = std::abs(v);
        double phase = std::arg(v) * 180.0 / pi;
        if (f > 0) {  // unwrap
          while (phase + offset[k] - previous_phase[k] > 180.0) offset[k] -= 360.0;
          while (phase + offset[k] - previous_phase[k] < -180.0) offset[k] += 360.0;
        }
        phase += offset[k];
        previous_phase[k] = phase;
        // A zero magnitude has no place on a log axis: written as missing ('?').
        if (magnitude > 0.0 && std::isfinite(magnitude))
          data << " " << magnitude << " " << phase;
        else
          data << " ? ?";
      }
      data << "\n";
    }
  }
  {
    std::ofstream script(script_path);
    if (!script) return Status::failure("cannot write " + script_path);
    script << terminal_for(path, 1000, 750) << "set datafile missing '?'\n"
           << "set multiplot layout 2,1 title " << quoted(title) << "\n"
           << "set grid\nset key inside left top opaque box\n"
           << (log_frequency ? "set logscale x\n" : "") << "set lmargin 12\n"
           << "set logscale y\nset format y '%.0e'\nset ylabel 'magnitude'\n"
           << "unset xlabel\n"
           << marker_lines(markers, "graph 0.92");
    script << "plot ";
    for (size_t k = 0; k < series.size(); ++k)
      script << (k ? ", " : "") << quoted(data_path) << " using 1:" << 2 + 2 * k
             << " with lines lw 2 title " << quoted(series[k].label + " [" + series[k].unit + "]");
    script << "\nunset logscale y\nset format y '%g'\nset ylabel 'phase [deg]'\n"
           << "set xlabel 'frequency [Hz]'\n"
           << marker_lines(markers, "graph 0.92") << "plot ";
    for (size_t k = 0; k < series.size(); ++k)
      script << (k ? ", " : "") << quoted(data_path) << " using 1:" << 3 + 2 * k
             << " with lines lw 2 title " << quoted(series[k].label);
    script << "\nunset multiplot\n";
  }
  return run_gnuplot(script_path, path);
}

Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::string& y_label,
                       const std::vector<LineSeries>& series,
                       const std::vector<PlotMarker>& markers) {
  const std::string data_path = path + ".dat", script_path = path + ".gp";
  {
    std::ofstream data(data_path);
    if (!data) return Status::failure("cannot write " + data_path);
    data.precision(10);
    for (const auto& s : series) {
      data << "# " << s.label << "\n";
      for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
        data << s.x[i] << " " << s.y[i] << "\n";
      data << "\n\n";  // gnuplot data blocks, addressed by index
    }
  }
  {
    std::ofstream script(script_path);
    if (!script) return Status::failure("cannot write " + script_path);
    script << terminal_for(path, 1000, 600) << "set title " << quoted(title) << "\n"
           << "set grid\nset key inside left top opaque box\n"
           << "set xlabel " << quoted(x_label) << "\nset ylabel " << quoted(y_label) << "\n"
           << marker_lines(markers, "graph 0.95") << "plot ";
    for (size_t k = 0; k < series.size(); ++k)
      script << (k ? ", " : "") << quoted(data_path) << " index " << k << " with lines lw 2 title "
             << quoted(series[k].label);
    script << "\n";
  }
  return run_gnuplot(script_path, path);
}

}  // namespace emnet
