// Scene reader: reads a TOML scene file (netlists/*.toml) plus `--set key=value` overrides into
// a validated, SI-valued emnet::Scene.
//
// Every problem (missing file, TOML syntax, unknown or missing key, wrong type, wrong or missing
// unit, out-of-range value, bad override) is thrown as an InputError naming the file and line
// (or "--set" for a value that came from an override), the dotted key and what was expected.
// Keys of array-of-tables entries are named by the entry's name where it has one, e.g.
// "dea[A].from", otherwise by index, e.g. "load[0].at".
#pragma once

#include <string>
#include <vector>

#include "emnet/errors.hpp"
#include "emnet/scene.hpp"

namespace emnet {

// Reads the scene file at `path` and applies `overrides`, each "dotted.key=value". The value
// is parsed as a TOML value when it is one (0.2, true, "70 mm", ["A", "B"]) and taken as a
// string otherwise (70mm, 70 mm, log). Plain keys are addressed as "beam.length", entries of
// [[dea]], [[probe]] and [[load]] by name or index: "dea.A.lever_arm", "dea[A].lever_arm",
// "load.0.value". An override may set a key the file lacks, but only one the schema knows.
// Throws InputError on any problem.
Scene read_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// The same for scene text already in memory; `display_name` stands for the file in messages
// and in Scene::file.
Scene read_scene_text(const std::string& text, const std::string& display_name,
                      const std::vector<std::string>& overrides = {});

}  // namespace emnet
