// Scene reader: reads a TOML scene file (netlists/*.toml) plus `--set key=value` overrides into
// a validated, SI-valued emnet::Scene.
//
// Every problem (missing file, TOML syntax, unknown or missing key, wrong type, wrong or missing
// unit, out-of-range value, bad override) is thrown as an InputError naming the file and line
// (or "override" for a value that came from an override, which each front-end shows in its own
// words), the dotted key and what was expected.
// Keys of array-of-tables entries are named by the entry's name where it has one, e.g.
// "dea[A].from", otherwise by index, e.g. "load[0].at".
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

// Bounds on a scene, so that reading any input takes bounded time and memory; each is
// inclusive ("at most"). Going over one is an InputError that names it.
namespace scene_limits {
inline constexpr std::size_t file_bytes = 4 * 1024 * 1024;  // a scene file (a regular file)
inline constexpr std::size_t line_bytes = 10000;            // one line of it
inline constexpr std::size_t key_bytes = 256;               // one key (a part of a dotted key)
inline constexpr std::size_t name_bytes = 64;               // dea[].name, probe[].name
// Tables within tables, parts of dotted keys and open arrays or inline tables, counted
// together from the document's root.
inline constexpr std::size_t nesting_depth = 64;
inline constexpr std::size_t tables_and_dotted_keys = 30000;  // [table] headers + dotted keys
inline constexpr std::size_t deas = 1000;                     // [[dea]] entries
inline constexpr std::size_t sections = 10000;                // [[section]] entries
inline constexpr std::size_t masses = 10000;                  // [[mass]] entries
inline constexpr std::size_t springs = 10000;                 // [[spring]] entries
inline constexpr std::size_t loads = 10000;                   // [[load]] entries
inline constexpr std::size_t probes = 10000;                  // [[probe]] entries
inline constexpr std::size_t circuit_elements = 10000;        // [[circuit]] entries
inline constexpr std::size_t pwl_points = 100000;             // points of one pwl waveform
inline constexpr std::size_t provenance_entries = 10000;      // keys in [provenance]
inline constexpr std::size_t overrides = 1000;                // --set KEY=VALUE
}  // namespace scene_limits

// Reads the scene file at `path` and applies `overrides`, each "dotted.key=value". The value
// is parsed as a TOML value when it is one (0.2, true, "70 mm", ["A", "B"]) and taken as a
// string otherwise (70mm, 70 mm, log). Plain keys are addressed as "beam.length", entries of
// [[dea]], [[probe]] and [[load]] by name or index: "dea.A.lever_arm", "dea[A].lever_arm",
// "load.0.value". An override may set a key the file lacks, but only one the parameter table
// (emnet/scene/parameters.hpp) knows.
// The file must be a regular file of at most scene_limits::file_bytes. Throws InputError on any
// problem.
Scene read_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// The bytes of the scene file at `path`: a regular file (not a directory, device or pipe) of
// at most scene_limits::file_bytes, read without reading past that. Throws InputError.
std::string read_scene_file(const std::string& path);

/// Files a scene names (a pwl waveform's CSV, `circuit[].file`) by the name the scene gives
/// them, with their contents.
using SceneFiles = std::map<std::string, std::string>;

/// The same as read_scene for scene text already in memory; `display_name` stands for the file in
/// messages and in Scene::file.
/// @param files  files the scene names, taken from here instead of the disk (for a scene rebuilt
///               in another process or directory from its text, which must compute what it
///               computed where it was read); a name not here is read from the disk
/// @throws InputError on any problem, naming the file, line and key
Scene read_scene_text(const std::string& text, const std::string& display_name,
                      const std::vector<std::string>& overrides = {}, const SceneFiles& files = {});

/// The files `scene` read (its pwl CSV files), rebuilt from the values it holds: CSV of the
/// shortest round-trip numbers, which read_scene_text turns back into the same values bit for bit.
SceneFiles scene_files(const Scene& scene);

}  // namespace emnet
