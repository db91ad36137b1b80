// gnuplot for one image: writes the plotted numbers and a gnuplot script, runs gnuplot on them
// under a time limit, and keeps the numbers (path + ".dat") and the script (path + ".gp") beside
// the image only when asked (src/report/gnuplot_script.hpp; the plots:
// include/emnet/report/plot.hpp).
//
// Every file is written completely or not at all (emnet::OutputFile), and so is the image:
// gnuplot runs on copies of the data and the script in a private directory beside the image
// (".emnet-plot-XXXXXX", mode 0700, made by mkdtemp: no other user can place, replace or read a
// file in it, whatever the image's directory allows), drawing into that directory; the drawing
// is renamed onto the image when gnuplot has succeeded and written a non-empty file, and only
// then are the asked-for data and script written beside it. A failure or a cancellation leaves
// the previous image, if any, never a half-written one, and no side files of a new one. The
// directory is removed afterwards (and by the command line when a signal ends it). gnuplot is
// started without a shell, through the process helper (emnet/core/process.hpp), as
//   gnuplot -d script.gp      (in the private directory, standard input /dev/null)
// under a time limit of 60 s that kills it and everything it started; its standard output and
// error are kept (the first 1 MiB) for the message when it fails. A saved script names its files
// relative to its directory, so it can be re-run from there.
// Every text from the caller goes into the script as a single-quoted gnuplot string (no
// backslash, backquote or macro expansion happens inside those) with control characters
// replaced by spaces and quotes doubled, and is drawn with `noenhanced` so '_', '^', '@', '{'
// are shown literally.
#include "gnuplot_script.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <locale>
#include <system_error>
#include <vector>

#include "emnet/core/output_file.hpp"
#include "emnet/core/process.hpp"
#include "emnet/core/temporary_files.hpp"

namespace emnet::gnuplot {

namespace {

constexpr int kGnuplotTimeLimitSeconds = 60;

std::string lowercase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

Status plot_files_for(const std::string& image_path, PlotFiles& files, bool animation) {
  // A name reaches the script (its header, `set output`, the data file's name): a control
  // character there would end a line of the script, so such a name is refused outright.
  for (const char c : image_path) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02x", byte);
      return Status::failure("plot file '" + one_line(image_path) +
                             "' holds a control character (byte " + code +
                             "); give a name without newlines, tabs or other control characters");
    }
  }
  const std::filesystem::path path(image_path);
  const std::string extension = lowercase(path.extension().string());
  if (extension == ".png") {
    files.format = ImageFormat::png;
  } else if (extension == ".svg") {
    files.format = ImageFormat::svg;
  } else if (extension == ".gif" && animation) {
    files.format = ImageFormat::gif;
  } else {
    return Status::failure("plot file '" + image_path +
                           "' must end in .png (PNG image) or .svg (SVG image)" +
                           (animation ? " or .gif (an animation)" : ""));
  }
  if (path.filename().empty())
    return Status::failure("plot path '" + image_path + "' names no file");
  files.directory = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  files.image_name = path.filename().string();
  files.data_name = files.image_name + ".dat";
  files.script_name = files.image_name + ".gp";
  files.data_path = image_path + ".dat";
  files.script_path = image_path + ".gp";
  files.image_path = image_path;
  return Status::success();
}

std::string one_line(const std::string& text) {
  std::string line = text;
  for (char& c : line) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) c = ' ';
  }
  return line;
}

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

std::string number_text(double value) {
  if (!std::isfinite(value)) return "NaN";
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(12);
  out << value;
  return out.str();
}

std::ostringstream classic_stream() {
  std::ostringstream stream;
  stream.imbue(std::locale::classic());
  return stream;
}

std::string gnuplot_terminal_line(const PlotFiles& files, int width, int height, int frame_delay) {
  std::ostringstream out;
  if (files.format == ImageFormat::png) {
    out << "set terminal pngcairo size " << width << "," << height
        << " enhanced font 'Sans,11' background rgb 'white'\n";
  } else if (files.format == ImageFormat::gif) {
    out << "set terminal gif animate delay " << frame_delay << " loop 0 optimize size " << width
        << "," << height << " background rgb 'white'\n";
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

namespace {

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

// Runs gnuplot on `script_name` in `directory` under a time limit (stopped when `output`'s
// progress is cancelled) and checks that it wrote a non-empty `image_path`; `gnuplot_missing`
// says that it could not be started.
Status run_gnuplot(const PlotFiles& files, const std::string& directory,
                   const std::string& script_name, const std::string& image_path,
                   const PlotOutput& output, bool& gnuplot_missing);

}  // namespace

Status write_script_and_run(const PlotFiles& files, const std::string& preamble,
                            const ScriptBody& body, const std::string& data,
                            const std::string& image_path, const PlotOutput& output) {
  if (cancel_requested(output.progress)) return cancelled_status();
  TemporaryDirectory work;
  if (Status made = work.create(files.directory.string(), ".emnet-plot-"); !made.ok())
    return Status::failure("cannot write '" + image_path + "': " + made.message);
  const std::string drawing_name =
      std::string("drawing") + (files.format == ImageFormat::png   ? ".png"
                                : files.format == ImageFormat::gif ? ".gif"
                                                                   : ".svg");
  const std::string drawing = work.path() + "/" + drawing_name;
  if (Status status = write_output_file(work.path() + "/data", data); !status.ok()) return status;
  if (Status status = write_output_file(
          work.path() + "/script.gp",
          preamble + "set output " + gnuplot_string(drawing_name) + "\n" + body("data"));
      !status.ok())
    return status;
  const auto write_side_files = [&] {
    if (Status status = write_output_file(files.data_path, data); !status.ok()) return status;
    return write_output_file(
        files.script_path,
        preamble + "set output " + gnuplot_string(files.image_name) + "\n" + body(files.data_name));
  };
  bool gnuplot_missing = false;
  if (Status status =
          run_gnuplot(files, work.path(), "script.gp", drawing, output, gnuplot_missing);
      !status.ok()) {
    // Without gnuplot the data and the script are still of use (drawn elsewhere).
    if (gnuplot_missing && output.data_and_script) {
      if (Status written = write_side_files(); !written.ok()) return written;
    }
    return status;
  }
  if (std::rename(drawing.c_str(), image_path.c_str()) != 0) {
    std::error_code error(errno, std::generic_category());
    return Status::failure("cannot write '" + image_path + "': " + error.message());
  }
  return output.data_and_script ? write_side_files() : Status::success();
}

namespace {

Status run_gnuplot(const PlotFiles& files, const std::string& directory,
                   const std::string& script_name, const std::string& image_path,
                   const PlotOutput& output_options, bool& gnuplot_missing) {
  const bool side_files = output_options.data_and_script;
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
  gnuplot.working_directory = directory;
  if (output_options.progress != nullptr)
    gnuplot.stop_requested = [&] { return cancel_requested(output_options.progress); };
  gnuplot.standard_output = keep;
  gnuplot.standard_error = keep;
  gnuplot.timeout_seconds = kGnuplotTimeLimitSeconds;
  const ProcessResult end = run_process(gnuplot);

  // What a message names: the saved script when there is one, else the image.
  const std::string& drawn = side_files ? files.script_path : files.image_path;
  const std::string details = last_lines(output, 8);
  const std::string output_note = details.empty() ? "" : ":\n  " + details;
  using How = ProcessResult::How;
  if (end.how == How::stopped) return cancelled_status();
  if (end.how == How::failed)
    return Status::failure("cannot run gnuplot for '" + drawn + "': " + end.problem);
  if (end.how == How::not_started) {
    gnuplot_missing = true;
    return Status::failure(
        "cannot run gnuplot: it is not installed or not on PATH (Debian package gnuplot-nox, "
        "installed by tools/setup-deps)" +
        (side_files ? "; the data and script are in '" + files.data_path + "' and '" +
                          files.script_path + "'"
                    : std::string()) +
        output_note);
  }
  if (end.how == How::timed_out) {
    return Status::failure("gnuplot did not finish within " +
                           std::to_string(kGnuplotTimeLimitSeconds) + " s on '" + drawn + "'");
  }
  if (end.how == How::signalled) {
    return Status::failure("gnuplot was killed by signal " + std::to_string(end.signal_number) +
                           " on '" + drawn + "'" + output_note);
  }
  if (end.exit_status != 0) {
    return Status::failure("gnuplot failed (exit code " + std::to_string(end.exit_status) +
                           ") on '" + drawn + "'" + output_note);
  }
  const auto size = std::filesystem::file_size(image_path, ignored);
  if (ignored || size == 0) {
    return Status::failure("gnuplot ran but did not write the image for '" + drawn + "'" +
                           output_note);
  }
  return Status::success();
}

}  // namespace

}  // namespace emnet::gnuplot
