// The scene reader's class, shared by its source files: scene_reader.cpp (every table but the
// circuit's) and circuit_reader.cpp ([[circuit]]: its nodes, waveforms and topology). Private to
// src/scene/.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene.hpp"
#include "toml_section.hpp"

namespace emnet {
namespace scene_reading {

// The DEA names of the scene read so far, and "the scene defines 'A', 'B'" for messages.
std::vector<std::string> dea_names(const Scene& scene);
std::string defined_deas(const std::vector<std::string>& names);

class SceneReader {
 public:
  // `files`: contents supplied for files the scene names (emnet::SceneFiles); may be null.
  SceneReader(const std::string& display_name, const std::map<std::string, std::string>* files)
      : locator_(display_name), files_(files) {}

  const Locator& locator() const { return locator_; }
  Scene read(const toml::table& root) const;

 private:
  // The entries of an array of tables, each with the prefix its keys are named by.
  struct Entry {
    const toml::table* table;
    std::string prefix;  // "dea[A]" or "load[0]"
  };
  std::vector<Entry> entries(const toml::table& root, const SceneTableInfo& table) const;
  Section section(const toml::table& root, const std::string& table_name) const;

  void check_top_level(const toml::table& root) const;
  void read_scene_table(const toml::table& root, Scene& scene) const;
  void read_beam(const toml::table& root, Scene& scene) const;
  void read_sections(const toml::table& root, Scene& scene) const;
  void read_masses(const toml::table& root, Scene& scene) const;
  void read_springs(const toml::table& root, Scene& scene) const;
  void read_damping(const toml::table& root, Scene& scene) const;
  void read_deas(const toml::table& root, Scene& scene) const;
  void read_drive(const toml::table& root, Scene& scene) const;
  void read_loads(const toml::table& root, Scene& scene) const;
  void read_probes(const toml::table& root, Scene& scene) const;
  // probe[].spring: a spring's name or its index (an integer, or digits in a string), checked
  // against the scene's [[spring]] entries; returned as written (an index as its digits).
  std::string read_probe_spring(const Section& reader, const Scene& scene) const;
  void read_circuit(const toml::table& root, Scene& scene) const;
  std::string read_circuit_node(const Section& reader, const std::string& end,
                                const Scene& scene) const;
  void read_waveform(const Section& reader, const toml::table& entry, Scene& scene,
                     std::size_t index) const;
  void check_circuit_topology(const toml::table& root, const Scene& scene) const;
  void read_ac(const toml::table& root, AcSpec& ac) const;
  void read_environment(const toml::table& root, Scene& scene) const;
  void read_model(const toml::table& root, Scene& scene) const;
  void read_provenance(const toml::table& root, Scene& scene) const;
  void read_provenance_table(const toml::table& table, const std::string& prefix,
                             Scene& scene) const;

  Locator locator_;
  const std::map<std::string, std::string>* files_;
};

}  // namespace scene_reading
}  // namespace emnet
