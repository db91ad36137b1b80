#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/common.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

// ---- schema ------------------------------------------------------------------------------
//
// `emnet schema [--markdown | --json]`: the scene's parameter table (emnet/scene/parameters.hpp),
// every key with its unit, default, range, users and meaning; no scene is read.

struct SchemaOptions {
  bool markdown = false;
  bool json = false;
};

int run_schema_command(const SchemaOptions& schema);

Command add_schema_command(CLI::App& app) {
  auto schema_options = std::make_shared<SchemaOptions>();
  SchemaOptions& schema = *schema_options;
  CLI::App* command = app.add_subcommand(
      "schema",
      "every scene key: its unit, default, range, which drive kinds or components use it and\n"
      "what it means (a text table; --markdown or --json)");
  auto* markdown = command->add_flag("--markdown", schema.markdown, "a Markdown table");
  command->add_flag("--json", schema.json, "a JSON array, one object per key")->excludes(markdown);
  return {command, [schema_options] { return run_schema_command(*schema_options); }};
}

int run_schema_command(const SchemaOptions& schema) {
  if (schema.markdown) {
    std::cout << emnet::parameter_listing_markdown();
  } else if (schema.json) {
    Json keys = Json::array();
    for (const auto& row : emnet::parameter_listing())
      keys.push_back({{"key", row.key},
                      {"kind", row.kind},
                      {"unit", row.unit},
                      {"default", row.default_text},
                      {"required", row.required},
                      {"range", row.range},
                      {"used_by", row.used_by},
                      {"meaning", row.meaning},
                      {"sensitivity", row.sensitivity}});
    std::cout << json_text(Json{{"keys", keys}}) << "\n";
  } else {
    std::cout << emnet::parameter_listing_text();
  }
  return 0;
}

}  // namespace emnet_cli
