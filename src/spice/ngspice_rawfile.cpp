// The rawfile of the ngspice program (`ngspice -b -r RAWFILE`), binary or ASCII, one plot or
// several after each other; see parse_ngspice_rawfile in emnet/spice/ngspice_runner.hpp.
//
// Each plot's header ("Title:", "Plotname:", "Flags:", "No. Variables:", "No. Points:",
// "Variables:" and its list) ends with "Binary:" (points × variables doubles, 16 bytes a value
// when the plot is complex, in the machine's byte order) or "Values:" (ASCII: "index<TAB>value"
// then one value per line, complex values as "re,im"). Before anything is allocated, the
// header's claim (points × variables) is checked against what the bytes after it can hold.
#include "ngspice_rawfile.hpp"

#include <charconv>
#include <complex>
#include <cstring>
#include <sstream>
#include <system_error>

#include "emnet/core/terminal_text.hpp"
#include "ngspice_messages.hpp"

namespace emnet {

std::string vector_name_from_rawfile(const std::string& rawfile_name) {
  std::string name = ngspice_lower_case(rawfile_name);
  if (name.size() > 3 && name.back() == ')') {
    if (name.rfind("v(", 0) == 0) return name.substr(2, name.size() - 3);
    if (name.rfind("i(", 0) == 0) return name.substr(2, name.size() - 3) + "#branch";
  }
  return name;
}

namespace {

bool parse_count(std::string_view text, std::size_t& count) {
  text = ngspice_trimmed(text);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), count);
  return error == std::errc() && end == text.data() + text.size();
}

bool parse_double(std::string_view text, double& value) {
  text = ngspice_trimmed(text);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

// What a plot's header says of its values: their counts and how they follow it.
struct PlotHeader {
  std::size_t variable_count = 0, point_count = 0;
  bool have_variables = false, have_points = false, binary = false, values = false;
};

// The rawfile's bytes read from the front: lines of the headers and of ASCII values, or the
// binary values. Each read gives false with the reason in `why` when the file is malformed.
class RawfileReader {
 public:
  explicit RawfileReader(const std::string& bytes) : bytes_(bytes) {}

  bool at_end() const { return position_ >= bytes_.size(); }

  bool next_line(std::string& line) {
    if (position_ >= bytes_.size()) return false;
    std::size_t end = bytes_.find('\n', position_);
    if (end == std::string::npos) end = bytes_.size();
    line = bytes_.substr(position_, end - position_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    position_ = end + 1;
    return true;
  }

  // A plot's header, up to and with its "Binary:" or "Values:" line (neither if the file ends).
  bool read_header(NgspiceRawPlot& plot, PlotHeader& header, std::string& why) {
    std::string line;
    while (next_line(line)) {
      if (ngspice_trimmed(line).empty()) continue;
      const std::size_t colon = line.find(':');
      const std::string key = colon == std::string::npos ? line : line.substr(0, colon);
      const std::string value =
          colon == std::string::npos ? "" : std::string(ngspice_trimmed(line.substr(colon + 1)));
      if (key == "Title") {
        plot.title = value;
      } else if (key == "Plotname") {
        plot.plot_name = value;
      } else if (key == "Flags") {
        plot.flags = value;
      } else if (key == "No. Variables") {
        // Once the list is read, its length is the count: a later count would contradict it.
        if (!plot.vectors.empty()) {
          why = "'No. Variables:' after the variable list";
          return false;
        }
        header.have_variables = parse_count(value, header.variable_count);
      } else if (key == "No. Points") {
        header.have_points = parse_count(value, header.point_count);
      } else if (key == "Variables") {
        if (!header.have_variables) {
          why = "'Variables:' before 'No. Variables:'";
          return false;
        }
        if (!plot.vectors.empty()) {
          why = "a second 'Variables:' list in one plot's header";
          return false;
        }
        if (!read_variables(plot, header.variable_count, why)) return false;
      } else if (key == "Binary") {
        header.binary = true;
        return true;
      } else if (key == "Values") {
        header.values = true;
        return true;
      }
    }
    return true;
  }

  // The header's claim against what the file holds, before anything is allocated: a binary
  // value takes 8 bytes (16 complex), an ASCII one at least 2 (a digit and a newline, which
  // the file's last value may lack).
  bool check_claim(const PlotHeader& header, bool complex, const std::string& plot_label,
                   std::string& why) const {
    const std::size_t per_value = value_size(header, complex);
    const std::size_t most_points =
        (available() + (header.binary ? 0 : 1)) / per_value / header.variable_count;
    if (header.point_count <= most_points) return true;
    why = plot_label + " is truncated: its header claims " + std::to_string(header.point_count) +
          " points of " + std::to_string(header.variable_count) + " variables, the " +
          std::to_string(available()) + " bytes after it hold at most " +
          std::to_string(most_points);
    return false;
  }

  // Binary: points × variables doubles (two a value when complex), in the machine's byte order.
  bool read_binary(NgspiceRawPlot& plot, const PlotHeader& header, bool complex,
                   const std::string& plot_label, std::string& why) {
    const std::size_t per_value = value_size(header, complex);
    const std::size_t needed = header.point_count * header.variable_count * per_value;
    if (available() < needed) {
      why = plot_label + " is truncated";
      return false;
    }
    for (std::size_t point = 0; point < header.point_count; ++point)
      for (NgspiceVector& vector : plot.vectors) {
        double parts[2] = {0.0, 0.0};
        std::memcpy(parts, bytes_.data() + position_, per_value);
        position_ += per_value;
        if (complex)
          vector.complex_values[point] = {parts[0], parts[1]};
        else
          vector.real_values[point] = parts[0];
      }
    return true;
  }

  // ASCII: "index<TAB>value" then one value per line; complex values as "re,im".
  bool read_ascii(NgspiceRawPlot& plot, const PlotHeader& header, bool complex,
                  const std::string& plot_label, std::string& why) {
    for (std::size_t point = 0; point < header.point_count; ++point)
      for (std::size_t index = 0; index < header.variable_count; ++index) {
        std::string text;
        do {
          if (!next_line(text)) {
            why = plot_label + " is truncated";
            return false;
          }
        } while (ngspice_trimmed(text).empty());
        if (index == 0) {
          const std::string_view rest = ngspice_trimmed(text);
          const std::size_t gap = rest.find_first_of(" \t");
          text = gap == std::string_view::npos ? "" : std::string(rest.substr(gap));
        }
        const std::size_t comma = text.find(',');
        double real = 0.0, imaginary = 0.0;
        const bool ok = comma == std::string::npos
                            ? parse_double(text, real)
                            : parse_double(std::string_view(text).substr(0, comma), real) &&
                                  parse_double(std::string_view(text).substr(comma + 1), imaginary);
        if (!ok) {
          why = "cannot read value '" + terminal_excerpt(text, 200) + "' in " + plot_label;
          return false;
        }
        NgspiceVector& vector = plot.vectors[index];
        if (complex)
          vector.complex_values[point] = {real, imaginary};
        else
          vector.real_values[point] = real;
      }
    return true;
  }

 private:
  // The variable list after "Variables:": "index name type" per line, the scale first.
  bool read_variables(NgspiceRawPlot& plot, std::size_t variable_count, std::string& why) {
    std::string line;
    for (std::size_t index = 0; index < variable_count; ++index) {
      if (!next_line(line)) {
        why = "the variable list ends early";
        return false;
      }
      std::istringstream fields(line);
      std::string number, name;
      if (!(fields >> number >> name)) {
        why = "cannot read variable line '" + terminal_excerpt(line, 200) + "'";
        return false;
      }
      NgspiceVector vector;
      vector.name = name;
      vector.is_scale = index == 0;
      plot.vectors.push_back(std::move(vector));
    }
    return true;
  }

  static std::size_t value_size(const PlotHeader& header, bool complex) {
    return header.binary ? (complex ? 2 * sizeof(double) : sizeof(double)) : std::size_t{2};
  }

  std::size_t available() const {
    return position_ <= bytes_.size() ? bytes_.size() - position_ : 0;
  }

  const std::string& bytes_;
  std::size_t position_ = 0;
};

// The counts a plot's values need: both given, the variable list as long as its count, and at
// least the scale.
bool check_counts(const NgspiceRawPlot& plot, const PlotHeader& header,
                  const std::string& plot_label, std::string& why) {
  if (!header.have_variables || !header.have_points ||
      plot.vectors.size() != header.variable_count) {
    why = plot_label + " lacks its variable or point count";
    return false;
  }
  if (header.variable_count == 0) {
    why = plot_label + " has no variables (not even its scale)";
    return false;
  }
  return true;
}

}  // namespace

bool parse_ngspice_rawfile(const std::string& bytes, std::vector<NgspiceRawPlot>& plots,
                           std::string& why) {
  RawfileReader reader(bytes);
  while (!reader.at_end()) {
    NgspiceRawPlot plot;
    PlotHeader header;
    if (!reader.read_header(plot, header, why)) return false;
    if (!header.binary && !header.values) {
      if (plots.empty()) why = "no 'Binary:' or 'Values:' section";
      return !plots.empty();
    }
    const std::string plot_label = "plot '" + terminal_excerpt(plot.plot_name, 200) + "'";
    if (!check_counts(plot, header, plot_label, why)) return false;
    const bool complex = plot.flags.find("complex") != std::string::npos;
    if (!reader.check_claim(header, complex, plot_label, why)) return false;
    for (NgspiceVector& vector : plot.vectors) {
      vector.is_complex = complex;
      if (complex)
        vector.complex_values.resize(header.point_count);
      else
        vector.real_values.resize(header.point_count);
    }
    const bool read = header.binary ? reader.read_binary(plot, header, complex, plot_label, why)
                                    : reader.read_ascii(plot, header, complex, plot_label, why);
    if (!read) return false;
    // The scale of a complex plot is a real frequency; ngspice 39 writes uninitialised bytes
    // in its imaginary half in binary rawfiles. It is zero, as libngspice reports it.
    if (complex && !plot.vectors.empty())
      for (std::complex<double>& value : plot.vectors.front().complex_values) value.imag(0.0);
    plots.push_back(std::move(plot));
  }
  return true;
}

}  // namespace emnet
