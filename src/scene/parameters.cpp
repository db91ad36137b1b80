// The scene's parameter table (emnet/scene/parameters.hpp): one entry per scene key, in the
// order of the scene's tables and, within a table, of its keys as the reader's messages list them.
// Each table's keys are in the file of the component they describe (src/scene/keys/); this file
// lists the tables in order.
#include "emnet/scene/parameters.hpp"

#include "scene/keys/scene_key_tables.hpp"

namespace emnet {

// Fluid properties at 20 °C and 101.325 kPa: water ρ = 998.2 kg/m³ (CRC Handbook of Chemistry
// and Physics, density of water), η = 1.002e-3 Pa·s (ISO/TR 3666:1998, the viscosity of water
// at 20 °C); dry air ρ = 1.204 kg/m³ (ideal gas, M = 28.96 g/mol), η = 1.81e-5 Pa·s (CRC
// Handbook, viscosity of air).
FluidProperties fluid_properties(Fluid fluid) {
  switch (fluid) {
    case Fluid::water:
      return {998.2, 1.002e-3};
    case Fluid::air:
      return {1.204, 1.81e-5};
    case Fluid::none:
      break;
  }
  return {};
}

namespace {

// Every table of a scene file with its keys, in the order of scene_tables().
std::vector<scene_keys::SceneTableKeys> tables_in_order() {
  using namespace scene_keys;
  return {scene_table_keys(),       beam_table_keys(),    section_table_keys(),
          mass_table_keys(),        spring_table_keys(),  damping_table_keys(),
          dea_table_keys(),         drive_table_keys(),   load_table_keys(),
          probe_table_keys(),       circuit_table_keys(), ac_table_keys(),
          environment_table_keys(), model_table_keys(),   provenance_table_keys()};
}

std::vector<ParameterInfo> every_key() {
  std::vector<ParameterInfo> keys;
  for (const scene_keys::SceneTableKeys& table : tables_in_order())
    keys.insert(keys.end(), table.keys.begin(), table.keys.end());
  return keys;
}

std::vector<SceneTableInfo> every_table() {
  std::vector<SceneTableInfo> tables;
  for (const scene_keys::SceneTableKeys& table : tables_in_order()) {
    tables.push_back(table.table);
    if (table.table.free_form) continue;
    for (const ParameterInfo& info : table.keys) tables.back().keys.push_back(info.name);
  }
  return tables;
}

}  // namespace

const std::vector<ParameterInfo>& parameter_table() {
  static const std::vector<ParameterInfo> table = every_key();
  return table;
}

const std::vector<SceneTableInfo>& scene_tables() {
  static const std::vector<SceneTableInfo> tables = every_table();
  return tables;
}

}  // namespace emnet
