// Plot writer: writes the plotted numbers (path + ".dat") and a gnuplot script (path + ".gp")
// beside the image, then runs gnuplot under a time limit; see include/emnet/report/plot.hpp.
//
// Data and script are written completely or not at all (emnet::OutputFile), and so is the
// image: gnuplot runs a hidden copy of the script whose only difference is its output, a
// temporary image beside the real one, which is renamed onto the image when gnuplot has
// succeeded and written a non-empty file; a failure leaves the previous image, if any, never a
// half-written one. gnuplot is started without a shell, through the process helper
// (emnet/core/process.hpp), as
//   gnuplot -d .NAME.gp.PID.run      (in DIRECTORY, standard input /dev/null)
// under a time limit of 60 s that kills it and everything it started; its standard output and
// error are kept (the first 1 MiB) for the message when it fails. The script names its files
// relative to its directory, so the saved one can be re-run from there.
// Every text from the caller goes into the script as a single-quoted gnuplot string (no
// backslash, backquote or macro expansion happens inside those) with control characters
// replaced by spaces and quotes doubled, and is drawn with `noenhanced` so '_', '^', '@', '{'
// are shown literally.
#include "emnet/report/plot.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "emnet/core/output_file.hpp"
#include "emnet/core/process.hpp"

namespace emnet {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kGnuplotTimeLimitSeconds = 60;

enum class ImageFormat { png, svg };

struct PlotFiles {
  ImageFormat format = ImageFormat::png;
  std::filesystem::path directory;  // where gnuplot runs; "." for a bare file name
  std::string image_name;           // file names relative to `directory`
  std::string data_name;
  std::string script_name;
  std::string data_path;  // full paths, for messages
  std::string script_path;
};

std::string lowercase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// Splits the image path into directory and file names; fails on an unknown extension.
Status plot_files_for(const std::string& image_path, PlotFiles& files) {
  const std::filesystem::path path(image_path);
  const std::string extension = lowercase(path.extension().string());
  if (extension == ".png") {
    files.format = ImageFormat::png;
  } else if (extension == ".svg") {
    files.format = ImageFormat::svg;
  } else {
    return Status::failure("plot file '" + image_path +
                           "' must end in .png (PNG image) or .svg (SVG image)");
  }
  if (path.filename().empty())
    return Status::failure("plot path '" + image_path + "' names no file");
  files.directory = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  files.image_name = path.filename().string();
  files.data_name = files.image_name + ".dat";
  files.script_name = files.image_name + ".gp";
  files.data_path = image_path + ".dat";
  files.script_path = image_path + ".gp";
  return Status::success();
}

// `text` on one line: each control character (newline, tab, ...) becomes a space.
std::string one_line(const std::string& text) {
  std::string line = text;
  for (char& c : line) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) c = ' ';
  }
  return line;
}

// `text` as a single-quoted gnuplot string: one line, each quote doubled. gnuplot expands
// neither backslashes, backquotes nor '@' macros inside single quotes.
std::string gnuplot_string(const std::string& text) {
  std::string quoted = "'";
  for (char c : one_line(text)) {
    if (c == '\'') {
      quoted += "''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

// A number as gnuplot reads it, independent of the global locale; NaN for a missing point.
std::string number_text(double value) {
  if (!std::isfinite(value)) return "NaN";
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(12);
  out << value;
  return out.str();
}

// A text stream for a data file or script, in the classic locale.
std::ostringstream classic_stream() {
  std::ostringstream stream;
  stream.imbue(std::locale::classic());
  return stream;
}

// A file that is removed when this goes out of scope (the script gnuplot runs, a temporary
// image not renamed into place).
class RemovedAtExit {
 public:
  explicit RemovedAtExit(std::string path) : path_(std::move(path)) {}
  ~RemovedAtExit() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  RemovedAtExit(const RemovedAtExit&) = delete;
  RemovedAtExit& operator=(const RemovedAtExit&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Terminal line of a script; `height` in pixels. The output line follows it (`set output`).
std::string gnuplot_terminal_line(const PlotFiles& files, int width, int height) {
  std::ostringstream out;
  if (files.format == ImageFormat::png) {
    out << "set terminal pngcairo size " << width << "," << height
        << " enhanced font 'Sans,11' background rgb 'white'\n";
  } else {
    out << "set terminal svg size " << width << "," << height
        << " dynamic enhanced font 'Sans,11' background rgb 'white'\n";
  }
  return out.str();
}

std::string script_header(const PlotFiles& files, const std::string& what,
                          const std::string& title) {
  std::ostringstream out;
  out << "# " << what << ": " << gnuplot_string(title) << "\n"
      << "# Data: " << files.data_name << " (beside this script). To re-draw " << files.image_name
      << " after editing,\n"
      << "# run in this directory: gnuplot " << files.script_name << "\n";
  return out.str();
}

// The last lines of gnuplot's output, for an error message.
std::string last_lines(const std::string& output, size_t count) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.find_first_not_of(" \t\r^") != std::string::npos)
      lines.push_back(line);
  }
  if (lines.size() > count) lines.erase(lines.begin(), lines.end() - count);
  std::string text;
  for (const auto& line : lines) text += (text.empty() ? "" : "\n  ") + line;
  return text;
}

// Runs gnuplot on the script `script_name` (in the image's directory) under a time limit and
// checks that it wrote a non-empty `image_path`.
Status run_gnuplot(const PlotFiles& files, const std::string& script_name,
                   const std::string& image_path);

// Writes the gnuplot script (`preamble`, the output line, `body`) beside the image, then runs a
// copy of it that draws into a temporary image and renames that onto the image.
Status write_script_and_run(const PlotFiles& files, const std::string& preamble,
                            const std::string& body, const std::string& image_path) {
  if (Status status =
          write_output_file(files.script_path, preamble + "set output " +
                                                   gnuplot_string(files.image_name) + "\n" + body);
      !status.ok)
    return status;
  const std::string unique = std::to_string(::getpid());
  const std::string run_name = "." + files.script_name + "." + unique + ".run";
  const std::string image_name = "." + files.image_name + "." + unique + ".drawing";
  const RemovedAtExit run_script((files.directory / run_name).string());
  const RemovedAtExit drawing((files.directory / image_name).string());
  if (Status status = write_output_file(
          run_script.path(), preamble + "set output " + gnuplot_string(image_name) + "\n" + body);
      !status.ok)
    return status;
  if (Status status = run_gnuplot(files, run_name, drawing.path()); !status.ok) return status;
  if (std::rename(drawing.path().c_str(), image_path.c_str()) != 0) {
    std::error_code error(errno, std::generic_category());
    return Status::failure("cannot write '" + image_path + "': " + error.message());
  }
  return Status::success();
}

Status run_gnuplot(const PlotFiles& files, const std::string& script_name,
                   const std::string& image_path) {
  std::error_code ignored;
  // gnuplot's standard output and error, in the order they come, the first 1 MiB.
  std::string output;
  const auto keep = ProcessOutput::to_callback([&](const char* data, std::size_t size) {
    output.append(data, std::min(size, (std::size_t{1} << 20) -
                                           std::min(output.size(), std::size_t{1} << 20)));
    return true;
  });
  ProcessOptions gnuplot;
  gnuplot.arguments = {"gnuplot", "-d", script_name};
  gnuplot.working_directory = files.directory.string();
  gnuplot.standard_output = keep;
  gnuplot.standard_error = keep;
  gnuplot.timeout_seconds = kGnuplotTimeLimitSeconds;
  const ProcessResult end = run_process(gnuplot);

  const std::string details = last_lines(output, 8);
  const std::string output_note = details.empty() ? "" : ":\n  " + details;
  using How = ProcessResult::How;
  if (end.how == How::failed)
    return Status::failure("cannot run gnuplot for '" + files.script_path + "': " + end.problem);
  if (end.how == How::not_started) {
    return Status::failure(
        "cannot run gnuplot: it is not installed or not on PATH (Debian package gnuplot-nox, "
        "installed by tools/setup-deps); the data and script are in '" +
        files.data_path + "' and '" + files.script_path + "'" + output_note);
  }
  if (end.how == How::timed_out) {
    return Status::failure("gnuplot did not finish within " +
                           std::to_string(kGnuplotTimeLimitSeconds) + " s on '" +
                           files.script_path + "'");
  }
  if (end.how == How::signalled) {
    return Status::failure("gnuplot was killed by signal " + std::to_string(end.signal_number) +
                           " on '" + files.script_path + "'" + output_note);
  }
  if (end.exit_status != 0) {
    return Status::failure("gnuplot failed (exit code " + std::to_string(end.exit_status) +
                           ") on '" + files.script_path + "'" + output_note);
  }
  const auto size = std::filesystem::file_size(image_path, ignored);
  if (ignored || size == 0) {
    return Status::failure("gnuplot ran but did not write the image for '" + files.script_path +
                           "'" + output_note);
  }
  return Status::success();
}

// Vertical dashed lines (and, with `with_labels`, labels beside them) for the markers inside
// [x_min, x_max]. A label reads upwards from the bottom of the panel, left of its line, on an
// opaque background: a marker usually sits at a resonance, where the curves are high, so the
// bottom of the panel is where the label is least likely to hide a curve.
std::string marker_lines(const std::vector<PlotMarker>& markers, double x_min, double x_max,
                         bool with_labels) {
  std::ostringstream out;
  int index = 1;
  for (const auto& marker : markers) {
    const double x = marker.frequency_hz;
    if (!std::isfinite(x) || x < x_min || x > x_max) continue;
    out << "set arrow " << index << " from " << number_text(x) << ", graph 0 to " << number_text(x)
        << ", graph 1 nohead front dt 2 lw 1.5 lc rgb '#b00000'\n";
    if (with_labels) {
      out << "set label " << index << " " << gnuplot_string(marker.label) << " at "
          << number_text(x)
          << ", graph 0.03 rotate by 90 left front offset -1.3,0 boxed noenhanced"
             " tc rgb '#b00000'\n";
    }
    ++index;
  }
  return out.str();
}

// Text box of the marker labels: opaque, so a label stays legible over a curve. (gnuplot 5.4
// leaves the box of rotated text unfilled when it has no border, hence the thin border.)
constexpr const char* kMarkerLabelStyle =
    "set style textbox opaque fillcolor 'white' border lc rgb '#b00000' lw 0.5 margins 1,1\n";

std::string unset_markers() {
  return "unset arrow\nunset label\n";
}

// "[lo:hi]" for a range of finite values, or "[*:*]" when there is nothing finite or one value.
std::string range_text(double lo, double hi) {
  if (!(lo < hi)) return "[*:*]";
  return "[" + number_text(lo) + ":" + number_text(hi) + "]";
}

// Phase step for the tics of an unwrapped phase axis spanning `span` degrees (0: automatic).
double phase_tic_step(double span) {
  if (span <= 360.0) return 45.0;
  if (span <= 1080.0) return 90.0;
  if (span <= 2160.0) return 180.0;
  return 0.0;
}

// The legend: one row of entries between the page title and the top panel, wrapped into as
// many rows as the label lengths need. Pixel sizes are for the 11-point Sans font.
struct LegendLayout {
  std::string key_line;  // "set key ..." line
  double panel_top = 0;  // screen fraction where the (top) panel starts, below the legend
};

LegendLayout legend_layout(const std::vector<std::string>& entries, int width_px, int height_px) {
  constexpr double kCharacterWidthPx = 7.5, kRowHeightPx = 19.0, kTitleHeightPx = 42.0;
  size_t longest = 1;
  for (const auto& entry : entries) longest = std::max(longest, one_line(entry).size());
  const double column_width_px = (static_cast<double>(longest) + 9.0) * kCharacterWidthPx;
  const size_t fitting = static_cast<size_t>(0.9 * width_px / column_width_px);
  const size_t columns = std::max<size_t>(1, std::min(entries.size(), fitting));
  const size_t rows = (entries.size() + columns - 1) / columns;
  const double key_top = 1.0 - kTitleHeightPx / height_px;
  LegendLayout layout;
  layout.key_line = "set key at screen 0.5, screen " + number_text(key_top) +
                    " center top horizontal maxcols " + std::to_string(columns) + " maxrows " +
                    std::to_string(rows) + " samplen 3 noenhanced\n";
  layout.panel_top = key_top - (static_cast<double>(rows) * kRowHeightPx + 12.0) / height_px;
  return layout;
}

}  // namespace

Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency) {
  PlotFiles files;
  if (Status status = plot_files_for(path, files); !status.ok) return status;
  if (series.empty()) return Status::failure("Bode plot '" + path + "': no series to plot");
  if (frequencies_hz.empty()) return Status::failure("Bode plot '" + path + "': no frequencies");
  for (const auto& one : series) {
    if (one.values.size() != frequencies_hz.size()) {
      return Status::failure("Bode plot '" + path + "': series '" + one.label + "' has " +
                             std::to_string(one.values.size()) + " values for " +
                             std::to_string(frequencies_hz.size()) + " frequencies");
    }
  }

  // Rows kept: finite frequencies (positive ones on a log axis).
  std::vector<size_t> rows;
  for (size_t f = 0; f < frequencies_hz.size(); ++f) {
    const double frequency = frequencies_hz[f];
    if (std::isfinite(frequency) && (!log_frequency || frequency > 0.0)) rows.push_back(f);
  }
  if (rows.empty()) {
    return Status::failure("Bode plot '" + path + "': no " +
                           std::string(log_frequency ? "positive finite" : "finite") +
                           " frequency to plot");
  }

  // Magnitude and unwrapped phase; zero or non-finite values are missing (NaN) points.
  const size_t series_count = series.size();
  std::vector<std::vector<double>> magnitude(series_count), phase_deg(series_count);
  double phase_min = std::numeric_limits<double>::infinity(), phase_max = -phase_min;
  bool any_magnitude = false;
  for (size_t k = 0; k < series_count; ++k) {
    bool have_previous = false;
    double previous_phase = 0.0;
    for (size_t f : rows) {
      const std::complex<double> value = series[k].values[f];
      const double size = std::abs(value);
      if (!(size > 0.0) || !std::isfinite(size)) {
        magnitude[k].push_back(std::nan(""));
        phase_deg[k].push_back(std::nan(""));
        continue;
      }
      double phase = std::arg(value) * 180.0 / kPi;
      if (have_previous) phase += 360.0 * std::round((previous_phase - phase) / 360.0);
      previous_phase = phase;
      have_previous = true;
      any_magnitude = true;
      phase_min = std::min(phase_min, phase);
      phase_max = std::max(phase_max, phase);
      magnitude[k].push_back(size);
      phase_deg[k].push_back(phase);
    }
  }

  std::ostringstream data = classic_stream();
  data << "# " << one_line(title) << "\n# frequency [Hz]";
  for (const auto& one : series) {
    data << " | |" << one_line(one.label) << "| [" << one_line(one.unit) << "] | phase of "
         << one_line(one.label) << " [deg]";
  }
  data << "\n# NaN: zero or non-finite value (no point on the log axis)\n";
  for (size_t row = 0; row < rows.size(); ++row) {
    data << number_text(frequencies_hz[rows[row]]);
    for (size_t k = 0; k < series_count; ++k) {
      data << ' ' << number_text(magnitude[k][row]) << ' ' << number_text(phase_deg[k][row]);
    }
    data << '\n';
  }
  if (Status status = write_output_file(files.data_path, data.str()); !status.ok) return status;

  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (size_t f : rows) {
    x_lo = std::min(x_lo, frequencies_hz[f]);
    x_hi = std::max(x_hi, frequencies_hz[f]);
  }
  std::string common_unit = series.front().unit;
  for (const auto& one : series) {
    if (one.unit != common_unit) common_unit.clear();
  }
  const std::string magnitude_label =
      common_unit.empty() ? "magnitude" : "magnitude [" + common_unit + "]";

  std::vector<std::string> legend_entries;
  for (const auto& one : series) {
    legend_entries.push_back(one.label + (one.unit.empty() ? "" : " [" + one.unit + "]"));
  }
  constexpr int kWidthPx = 1000, kHeightPx = 750;
  const LegendLayout legend = legend_layout(legend_entries, kWidthPx, kHeightPx);
  // Panels stacked from legend.panel_top down to kBottom, kGap apart, of equal height.
  constexpr double kBottom = 0.09, kGap = 0.06;
  const double panel_height = (legend.panel_top - kBottom - kGap) / 2.0;
  const double magnitude_bottom = kBottom + panel_height + kGap;

  const std::string preamble =
      script_header(files, "Bode plot", title) + gnuplot_terminal_line(files, kWidthPx, kHeightPx);
  std::ostringstream script = classic_stream();
  script << "set datafile missing 'NaN'\n"
         << "set multiplot title " << gnuplot_string(title) << " font ',13' noenhanced\n"
         << "set lmargin at screen 0.10\nset rmargin at screen 0.97\n"
         << "set xrange " << range_text(x_lo, x_hi) << "\n"
         << (log_frequency ? "set logscale x\n" : "") << "set grid xtics ytics mytics\n"
         << "set border lw 1\n"
         << kMarkerLabelStyle;

  // Top panel: magnitude.
  script << "\n# Magnitude\n"
         << "set tmargin at screen " << number_text(legend.panel_top) << "\nset bmargin at screen "
         << number_text(magnitude_bottom) << "\n"
         << "set format x ''\nunset xlabel\n"
         << "set logscale y\nset ylabel " << gnuplot_string(magnitude_label) << " noenhanced\n"
         << (any_magnitude ? ""
                           : "set yrange [0.1:10]\nset label 99 'no non-zero values to plot' at "
                             "graph 0.5, graph 0.5 center\n")
         << "set format y '%h'\n"
         << legend.key_line << marker_lines(markers, x_lo, x_hi, true) << "plot ";
  for (size_t k = 0; k < series_count; ++k) {
    script << (k ? ", \\\n     " : "") << gnuplot_string(files.data_name)
           << " using 1:" << 2 + 2 * k << " with lines lw 2 lc " << k + 1 << " title "
           << gnuplot_string(legend_entries[k]);
  }

  // Bottom panel: unwrapped phase.
  const double step = any_magnitude ? phase_tic_step(phase_max - phase_min) : 45.0;
  script << "\n\n# Phase (unwrapped along frequency)\n"
         << unset_markers() << "set tmargin at screen " << number_text(kBottom + panel_height)
         << "\nset bmargin at screen " << number_text(kBottom) << "\n"
         << "set format x '% h'\nset xlabel 'frequency [Hz]'\n"
         << "unset logscale y\nset format y '% h'\nset yrange [*:*]\n"
         << "set ylabel 'phase [deg]'\n"
         << (any_magnitude ? "" : "set yrange [-180:180]\n")
         << (step > 0.0 ? "set ytics " + number_text(step) + "\n" : "") << "unset key\n"
         << marker_lines(markers, x_lo, x_hi, false) << "plot ";
  for (size_t k = 0; k < series_count; ++k) {
    script << (k ? ", \\\n     " : "") << gnuplot_string(files.data_name)
           << " using 1:" << 3 + 2 * k << " with lines lw 2 lc " << k + 1 << " notitle";
  }
  script << "\n\nunset multiplot\n";

  return write_script_and_run(files, preamble, script.str(), path);
}

Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::string& y_label,
                       const std::vector<LineSeries>& series,
                       const std::vector<PlotMarker>& markers) {
  PlotFiles files;
  if (Status status = plot_files_for(path, files); !status.ok) return status;
  if (series.empty()) return Status::failure("line plot '" + path + "': no series to plot");
  for (const auto& one : series) {
    if (one.x.size() != one.y.size()) {
      return Status::failure("line plot '" + path + "': series '" + one.label + "' has " +
                             std::to_string(one.x.size()) + " x values and " +
                             std::to_string(one.y.size()) + " y values");
    }
  }

  // One data block per series (gnuplot `index k`), separated by two blank lines.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  bool any_point = false;
  std::ostringstream data = classic_stream();
  data << "# " << one_line(title) << "\n# columns: " << one_line(x_label) << " | "
       << one_line(y_label)
       << "; one block per series (gnuplot index 0, 1, ...); NaN: missing point\n";
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& one = series[k];
    data << (k ? "\n\n" : "") << "# index " << k << ": " << one_line(one.label) << "\n";
    for (size_t i = 0; i < one.x.size(); ++i) {
      const bool finite = std::isfinite(one.x[i]) && std::isfinite(one.y[i]);
      data << number_text(finite ? one.x[i] : std::nan("")) << ' '
           << number_text(finite ? one.y[i] : std::nan("")) << '\n';
      if (finite) {
        any_point = true;
        x_lo = std::min(x_lo, one.x[i]);
        x_hi = std::max(x_hi, one.x[i]);
      }
    }
    if (one.x.empty()) data << "NaN NaN\n";  // keeps the block, so the indices stay in step
  }
  if (Status status = write_output_file(files.data_path, data.str()); !status.ok) return status;

  std::vector<std::string> legend_entries;
  for (const auto& one : series) legend_entries.push_back(one.label);
  constexpr int kWidthPx = 1000, kHeightPx = 650;
  const LegendLayout legend = legend_layout(legend_entries, kWidthPx, kHeightPx);

  const std::string preamble =
      script_header(files, "Line plot", title) + gnuplot_terminal_line(files, kWidthPx, kHeightPx);
  std::ostringstream script = classic_stream();
  script << "set datafile missing 'NaN'\n"
         << "set multiplot title " << gnuplot_string(title) << " font ',13' noenhanced\n"
         << "set lmargin at screen 0.09\nset rmargin at screen 0.97\n"
         << "set tmargin at screen " << number_text(legend.panel_top)
         << "\nset bmargin at screen 0.11\n"
         << "set xlabel " << gnuplot_string(x_label) << " noenhanced\n"
         << "set ylabel " << gnuplot_string(y_label) << " noenhanced\n"
         << "set grid xtics ytics\nset border lw 1\n"
         << kMarkerLabelStyle
         << (any_point ? "set xrange " + range_text(x_lo, x_hi) + "\n"
                       : "set xrange [0:1]\nset yrange [0:1]\n")
         << legend.key_line << marker_lines(markers, x_lo, x_hi, true) << "plot ";
  for (size_t k = 0; k < series.size(); ++k) {
    script << (k ? ", \\\n     " : "") << gnuplot_string(files.data_name) << " index " << k
           << " using 1:2 with lines lw 2 lc " << k + 1 << " title "
           << gnuplot_string(series[k].label);
  }
  script << "\n\nunset multiplot\n";

  return write_script_and_run(files, preamble, script.str(), path);
}

}  // namespace emnet
