// The scene reader's [[circuit]] table (emnet/scene/scene.hpp, CircuitSpec): each element's
// nodes (ground, the DEA terminals "dea.X", names of the circuit's own), its source waveform
// (inline, or a pwl from a CSV file), and the circuit's topology checks (no loop of voltage
// sources, a DC path to ground from every node). Part of the reader (scene_reader.cpp).
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "emnet/core/bounded_file.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "parameter_relations.hpp"
#include "scene_reader_internal.hpp"
#include "scene_text.hpp"

namespace emnet {
namespace scene_reading {

using scene_text::did_you_mean;
using scene_text::format_number;
using scene_text::is_identifier;
using scene_text::quoted_list;
using scene_text::trim;

namespace {

// A pwl waveform's points from the CSV file `file` (as the scene wrote it, relative to the
// folder of `scene_path`): time [s] and value [SI] per line, separated by a comma, semicolon,
// tab or spaces; blank lines and lines starting with '#' skipped; one header line (the first
// line that is not two numbers, before any data) allowed. Errors name the file and line; `key`
// is the scene key that names the file ("circuit[amp].file").
// `supplied`: the file's contents when the caller gave them (emnet::SceneFiles), else null.
std::vector<std::pair<double, double>> read_pwl_csv(const std::string& scene_path,
                                                    const std::string& file, const std::string& key,
                                                    const std::string* supplied) {
  namespace fs = std::filesystem;
  const fs::path path = fs::path(scene_path).parent_path() / fs::path(file);
  const std::string shown = path.string();
  if (supplied != nullptr && supplied->size() > scene_limits::file_bytes)
    throw InputError(shown, key,
                     "the pwl file '" + file + "' is " + std::to_string(supplied->size()) +
                         " bytes; at most " + std::to_string(scene_limits::file_bytes));
  std::istringstream stream(supplied != nullptr
                                ? *supplied
                                : read_bounded_regular_file(shown, scene_limits::file_bytes,
                                                            "the pwl file '" + file + "'", key));
  std::vector<std::pair<double, double>> points;
  std::string line;
  std::size_t line_number = 0;
  bool header_seen = false;
  while (std::getline(stream, line)) {
    ++line_number;
    const std::string where = shown + ":" + std::to_string(line_number);
    std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;
    for (char& c : text)
      if (c == ',' || c == ';' || c == '\t') c = ' ';
    std::istringstream fields(text);
    std::string first, second, extra;
    fields >> first >> second >> extra;
    auto number = [](const std::string& field, double& value) {
      if (field.empty()) return false;
      errno = 0;
      char* end = nullptr;
      value = std::strtod(field.c_str(), &end);
      return end == field.c_str() + field.size() && errno != ERANGE;
    };
    double time = 0.0, value = 0.0;
    const bool numbers = number(first, time) && number(second, value) && extra.empty();
    if (!numbers) {
      if (points.empty() && !header_seen) {
        header_seen = true;  // a header line ("time,voltage")
        continue;
      }
      throw InputError(where, key,
                       "expected two numbers, time [s] and value [SI], separated by a comma; "
                       "got '" +
                           terminal_excerpt(trim(line), 60) + "'");
    }
    if (!std::isfinite(time) || !std::isfinite(value))
      throw InputError(
          where, key,
          "the time and value must be finite, got '" + terminal_excerpt(trim(line), 60) + "'");
    if (time < 0.0)
      throw InputError(where, key, "the time must be >= 0 s, got " + format_number(time) + " s");
    if (!points.empty() && !(time > points.back().first))
      throw InputError(where, key,
                       "the time " + format_number(time) + " s is not after the previous line's " +
                           format_number(points.back().first) + " s (times must increase)");
    if (points.size() >= scene_limits::pwl_points)
      throw InputError(where, key,
                       "more than " + std::to_string(scene_limits::pwl_points) +
                           " points; a pwl waveform may have at most " +
                           std::to_string(scene_limits::pwl_points));
    points.emplace_back(time, value);
  }
  if (points.empty()) throw InputError(shown, key, "the pwl file '" + file + "' has no points");
  return points;
}

// A union-find over circuit node indices (0 is ground).
class NodeSets {
 public:
  explicit NodeSets(std::size_t count) : parent_(count) {
    for (std::size_t k = 0; k < count; ++k) parent_[k] = k;
  }
  std::size_t find(std::size_t k) {
    while (parent_[k] != k) k = parent_[k] = parent_[parent_[k]];
    return k;
  }
  // false when a and b were joined already (the new edge closes a loop)
  bool join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[a] = b;
    return true;
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace

std::string SceneReader::read_circuit_node(const Section& reader, const std::string& end,
                                           const Scene& scene) const {
  const std::string node = reader.string(end);
  if (is_ground_node_name(node)) return node;
  const std::string dea = dea_of_node_name(node);
  if (node.compare(0, 4, "dea.") == 0) {
    const std::vector<std::string> known = dea_names(scene);
    if (std::find(known.begin(), known.end(), dea) == known.end())
      reader.fail(end, "'" + node + "' names DEA '" + dea + "', which the scene does not have" +
                           did_you_mean(dea, known) + "; " + defined_deas(known));
    const DriveSpec& drive = scene.drive;
    if (drive.kind != DriveKind::none &&
        std::find(drive.deas.begin(), drive.deas.end(), dea) != drive.deas.end())
      reader.fail(end, "'" + node + "': DEA '" + dea +
                           "' is driven by the [drive] (drive.deas, drive.kind = '" +
                           drive_kind_name(drive.kind) +
                           "'); a DEA is driven by the drive or by a circuit, not both: take it "
                           "out of drive.deas, or the circuit off its terminal");
    return node;
  }
  if (!is_identifier(node) || node.size() > scene_limits::name_bytes)
    reader.fail(end,
                "must be \"ground\" (or \"0\"), \"dea.NAME\" or a node name of letters, "
                "digits and '_' (at most " +
                    std::to_string(scene_limits::name_bytes) + " characters), got '" + node + "'");
  return node;
}

// A source's waveform keys (those of circuit[].waveform; parameter_unused_reason has refused
// the others already).
void SceneReader::read_waveform(const Section& reader, const toml::table& entry, Scene& scene,
                                std::size_t index) const {
  auto key = [](const char* name) -> const ParameterInfo& {
    return parameter_info("circuit", name);
  };
  auto level = [&](const char* name) {
    const ParameterInfo& info = key(name);
    return reader.quantity(info, parameter_dimension(info, scene, index));
  };
  WaveformSpec& waveform = scene.circuit[index].waveform;
  switch (waveform.kind) {
    case WaveformKind::dc:
      break;
    case WaveformKind::square:
    case WaveformKind::pulse:
      waveform.low = level("low");
      waveform.high = level("high");
      waveform.rise = reader.quantity(key("rise"));
      waveform.fall = reader.optional_quantity(key("fall"));
      waveform.delay = reader.quantity(key("delay"));
      if (waveform.kind == WaveformKind::square) {
        waveform.frequency = reader.quantity(key("frequency"));
        waveform.duty = reader.quantity(key("duty"));
      } else {
        waveform.width = reader.quantity(key("width"));
        waveform.period = reader.quantity(key("period"));
      }
      break;
    case WaveformKind::sine:
      waveform.offset = level("offset");
      waveform.amplitude = level("amplitude");
      waveform.frequency = reader.quantity(key("frequency"));
      waveform.phase_degrees = reader.quantity(key("phase"));
      waveform.delay = reader.quantity(key("delay"));
      break;
    case WaveformKind::pwl: {
      const bool inline_points = reader.has("points"), from_file = reader.has("file");
      if (inline_points && from_file)
        reader.fail("file",
                    "give the pwl waveform's points inline (points) or from a file "
                    "(file), not both");
      if (!inline_points && !from_file)
        reader.fail("points",
                    "missing: waveform \"pwl\" needs points = [[\"0 s\", \"0 V\"], "
                    "...] or file = \"NAME.csv\"");
      if (from_file) {
        waveform.file = reader.string("file");
        const std::string* supplied = nullptr;
        if (files_ != nullptr) {
          if (const auto found = files_->find(waveform.file); found != files_->end())
            supplied = &found->second;
        }
        waveform.points =
            read_pwl_csv(locator_.display_name(), waveform.file, reader.key("file"), supplied);
        break;
      }
      const toml::array* array = entry.get_as<toml::array>("points");
      if (array == nullptr)
        reader.fail("points",
                    "must be an array of [time, value] pairs such as [[\"0 s\", \"0 V\"], "
                    "[\"1 ms\", \"3 kV\"]], got " +
                        describe_node(*reader.find("points")));
      if (array->size() > scene_limits::pwl_points)
        reader.fail("points", std::to_string(array->size()) +
                                  " points; a pwl waveform may have at most " +
                                  std::to_string(scene_limits::pwl_points));
      const Dimension unit = parameter_dimension(key("low"), scene, index);
      for (std::size_t k = 0; k < array->size(); ++k) {
        const toml::node& point = *array->get(k);
        const toml::array* pair = point.as_array();
        const std::string which = "point " + std::to_string(k + 1);
        if (pair == nullptr || pair->size() != 2)
          locator_.fail(&point, reader.key("points"),
                        which + " must be a pair [time, value], got " + describe_node(point));
        const double time =
            reader.node_quantity(*pair->get(0), "points", dim::time, which + "'s time");
        const double value =
            reader.node_quantity(*pair->get(1), "points", unit, which + "'s value");
        if (time < 0.0)
          locator_.fail(&point, reader.key("points"),
                        which + "'s time must be >= 0 s, got " + format_quantity(time, dim::time));
        waveform.points.emplace_back(time, value);
      }
      break;
    }
  }
}

void SceneReader::read_circuit(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("circuit");
  auto key = [](const char* name) -> const ParameterInfo& {
    return parameter_info("circuit", name);
  };
  std::set<std::string> names;
  for (const Entry& entry : entries(root, table)) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    scene.circuit.emplace_back();
    const std::size_t index = scene.circuit.size() - 1;
    CircuitSpec& element = scene.circuit.back();
    element.name = reader.identifier("name");
    if (!names.insert(element.name).second)
      reader.fail("name", "duplicate circuit element name '" + element.name + "'");
    element.kind = reader.choice(
        key("kind"), std::vector<CircuitKind>{CircuitKind::resistor, CircuitKind::capacitor,
                                              CircuitKind::inductor, CircuitKind::voltage_source,
                                              CircuitKind::current_source});
    if (is_source(element.kind))
      element.waveform.kind =
          reader
              .optional_choice(key("waveform"),
                               std::vector<WaveformKind>{WaveformKind::dc, WaveformKind::sine,
                                                         WaveformKind::square, WaveformKind::pulse,
                                                         WaveformKind::pwl})
              .value_or(WaveformKind::dc);
    // A key this element (its kind, its waveform) does not use is refused with the reason.
    for (const std::string& name : table.keys)
      reader.reject_if_unused(key(name.c_str()), scene, index);
    element.from = read_circuit_node(reader, "from", scene);
    element.to = read_circuit_node(reader, "to", scene);
    const bool both_ground = is_ground_node_name(element.from) && is_ground_node_name(element.to);
    if (element.from == element.to || both_ground)
      reader.fail("to", "is the element's other end too ('" + element.from +
                            "'): an element between a node and itself does nothing");
    const ParameterInfo& value = key("value");
    if (parameter_unused_reason(value, scene, index).empty())
      element.value = reader.quantity(value, parameter_dimension(value, scene, index));
    if (is_source(element.kind)) {
      read_waveform(reader, *entry.table, scene, index);
      const ParameterInfo& ac = key("ac");
      element.ac = reader.quantity(ac, parameter_dimension(ac, scene, index));
    }
    if (const auto violation = circuit_element_violation(element))
      reader.fail(violation->name, violation->message);
  }
  if (scene.circuit.empty()) return;
  if (!scene.drive.electrical_dynamics && !scene.drive.electrical_dynamics_auto) {
    const Section drive = section(root, "drive");
    drive.fail("electrical_dynamics",
               "is false, but the scene has [[circuit]] elements, which act through the DEAs' "
               "electrical loops: set it true (or \"auto\")");
  }
  check_circuit_topology(root, scene);
}

// Every circuit node is touched by two element ends at least (a DEA terminal counts its DEA),
// reaches ground through resistors, inductors and voltage sources (a DEA's loop is a capacitor
// at DC), and no loop is made of voltage sources and inductors only: otherwise the static state
// is undefined (the static matrix is singular), which is said here by the node's name.
void SceneReader::check_circuit_topology(const toml::table& root, const Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("circuit");
  const std::vector<Entry> list = entries(root, table);
  std::map<std::string, std::size_t> index_of;  // node name -> index; 0 is ground
  struct End {
    std::size_t element;
    const char* key;
  };
  std::vector<std::vector<End>> touched(1);
  auto node_index = [&](const std::string& name, std::size_t element, const char* end) {
    if (is_ground_node_name(name)) return std::size_t{0};
    auto [at, added] = index_of.emplace(name, touched.size());
    if (added) touched.emplace_back();
    touched[at->second].push_back({element, end});
    return at->second;
  };
  std::vector<std::pair<std::size_t, std::size_t>> ends;
  for (std::size_t k = 0; k < scene.circuit.size(); ++k)
    ends.emplace_back(node_index(scene.circuit[k].from, k, "from"),
                      node_index(scene.circuit[k].to, k, "to"));
  auto fail_at = [&](const End& end, const std::string& message) {
    const Section reader(locator_, list[end.element].table, list[end.element].prefix);
    reader.fail(end.key, message);
  };
  for (const auto& [name, index] : index_of) {
    const bool dea_terminal = !dea_of_node_name(name).empty();
    if (touched[index].size() + (dea_terminal ? 1 : 0) < 2)
      fail_at(touched[index].front(),
              "node '" + name +
                  "' is touched by this element only (a dangling end, which carries no current): "
                  "connect it to another element, \"ground\" or a \"dea.NAME\" terminal");
  }
  NodeSets direct_current(touched.size()), sources_and_inductors(touched.size());
  for (std::size_t k = 0; k < scene.circuit.size(); ++k) {
    const CircuitKind kind = scene.circuit[k].kind;
    if (kind == CircuitKind::capacitor || kind == CircuitKind::current_source) continue;
    direct_current.join(ends[k].first, ends[k].second);
    if (kind == CircuitKind::resistor) continue;
    if (!sources_and_inductors.join(ends[k].first, ends[k].second))
      fail_at({k, "to"},
              "closes a loop of voltage sources and inductors only: at DC the "
              "inductors are shorts, so the loop has no static state; put a resistor "
              "in it");
  }
  for (const auto& [name, index] : index_of)
    if (direct_current.find(index) != direct_current.find(0))
      fail_at(touched[index].front(),
              "node '" + name +
                  "' has no DC path to ground through resistors, inductors or voltage sources "
                  "(capacitors, current sources and a DEA's film carry no direct current), so "
                  "its static voltage is undefined: add a resistor from it to ground (a leak "
                  "resistance) or to a driven node");
}

}  // namespace scene_reading
SceneFiles scene_files(const Scene& scene) {
  SceneFiles files;
  for (const CircuitSpec& element : scene.circuit) {
    const WaveformSpec& waveform = element.waveform;
    if (waveform.kind != WaveformKind::pwl || waveform.file.empty()) continue;
    std::string text = "# time [s], value [SI]: the points emnet read from this file\n";
    // std::to_chars: the shortest text that reads back as the same double, in no locale.
    char number[32];
    const auto append = [&](double x, char after) {
      text.append(number, std::to_chars(number, number + sizeof number, x).ptr);
      text += after;
    };
    for (const auto& [time, value] : waveform.points) {
      append(time, ',');
      append(value, '\n');
    }
    files[waveform.file] = std::move(text);
  }
  return files;
}

}  // namespace emnet
