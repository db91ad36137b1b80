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

bool parse_ngspice_rawfile(const std::string& bytes, std::vector<NgspiceRawPlot>& plots,
                           std::string& why) {
  std::size_t position = 0;
  const auto next_line = [&](std::string& line) {
    if (position >= bytes.size()) return false;
    std::size_t end = bytes.find('\n', position);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(position, end - position);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    position = end + 1;
    return true;
  };
  const auto parse_count = [](std::string_view text, std::size_t& count) {
    text = ngspice_trimmed(text);
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), count);
    return error == std::errc() && end == text.data() + text.size();
  };
  const auto parse_double = [](std::string_view text, double& value) {
    text = ngspice_trimmed(text);
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size();
  };

  while (position < bytes.size()) {
    NgspiceRawPlot plot;
    std::size_t variable_count = 0, point_count = 0;
    bool have_variables = false, have_points = false, binary = false, values = false;
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
        have_variables = parse_count(value, variable_count);
      } else if (key == "No. Points") {
        have_points = parse_count(value, point_count);
      } else if (key == "Variables") {
        if (!have_variables) {
          why = "'Variables:' before 'No. Variables:'";
          return false;
        }
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
      } else if (key == "Binary") {
        binary = true;
        break;
      } else if (key == "Values") {
        values = true;
        break;
      }
    }
    if (!binary && !values) {
      if (plots.empty()) why = "no 'Binary:' or 'Values:' section";
      return !plots.empty();
    }
    const std::string plot_label = "plot '" + terminal_excerpt(plot.plot_name, 200) + "'";
    if (!have_variables || !have_points || plot.vectors.size() != variable_count) {
      why = plot_label + " lacks its variable or point count";
      return false;
    }
    if (variable_count == 0) {
      why = plot_label + " has no variables (not even its scale)";
      return false;
    }
    // The header's claim against what the file holds, before anything is allocated: a binary
    // value takes 8 bytes (16 complex), an ASCII one at least 2 (a digit and a newline, which
    // the file's last value may lack).
    const bool complex = plot.flags.find("complex") != std::string::npos;
    const std::size_t per_value =
        binary ? (complex ? 2 * sizeof(double) : sizeof(double)) : std::size_t{2};
    const std::size_t available = position <= bytes.size() ? bytes.size() - position : 0;
    const std::size_t most_points = (available + (binary ? 0 : 1)) / per_value / variable_count;
    if (point_count > most_points) {
      why = plot_label + " is truncated: its header claims " + std::to_string(point_count) +
            " points of " + std::to_string(variable_count) + " variables, the " +
            std::to_string(available) + " bytes after it hold at most " +
            std::to_string(most_points);
      return false;
    }
    for (NgspiceVector& vector : plot.vectors) {
      vector.is_complex = complex;
      if (complex)
        vector.complex_values.resize(point_count);
      else
        vector.real_values.resize(point_count);
    }
    if (binary) {
      const std::size_t needed = point_count * variable_count * per_value;  // <= available
      if (bytes.size() - position < needed) {
        why = plot_label + " is truncated";
        return false;
      }
      for (std::size_t point = 0; point < point_count; ++point)
        for (NgspiceVector& vector : plot.vectors) {
          double parts[2] = {0.0, 0.0};
          std::memcpy(parts, bytes.data() + position, per_value);
          position += per_value;
          if (complex)
            vector.complex_values[point] = {parts[0], parts[1]};
          else
            vector.real_values[point] = parts[0];
        }
    } else {
      // ASCII: "index<TAB>value" then one value per line; complex values as "re,im".
      for (std::size_t point = 0; point < point_count; ++point)
        for (std::size_t index = 0; index < variable_count; ++index) {
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
          const bool ok =
              comma == std::string::npos
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
    }
    // The scale of a complex plot is a real frequency; ngspice 39 writes uninitialised bytes
    // in its imaginary half in binary rawfiles. It is zero, as libngspice reports it.
    if (complex && !plot.vectors.empty())
      for (std::complex<double>& value : plot.vectors.front().complex_values) value.imag(0.0);
    plots.push_back(std::move(plot));
  }
  return true;
}

}  // namespace emnet
