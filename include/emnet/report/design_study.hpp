// A design study's table (emnet/studies/design_study.hpp) as a CSV file or JSON.
//
// Columns, in order: variant (0-based), each varied key (SI, its unit in the JSON), status ("ok"
// or "failed: <why>"), validity ("within", or "OUTSIDE: " and each violation's message; empty
// for a failed variant), then the study's result columns. A failed variant's result fields are
// empty in the CSV and null in the JSON. Numbers are written with %.17g, so that reading them
// back gives the same doubles.
#pragma once

#include <string>

#include "emnet/core/errors.hpp"
#include "emnet/report/json.hpp"
#include "emnet/studies/design_study.hpp"

namespace emnet {

/// A computed variant's validity as the table writes it (see above).
std::string validity_text(const VariantResult& row);

/// The table's header: "variant", the keys, "status", "validity", the result columns.
std::vector<std::string> design_study_header(const DesignStudyResult& result);

/// The table as a CSV file at `path`.
/// Written completely or not at all; a failure is the returned Status (emnet/report/csv.hpp).
Status write_design_study_csv(const std::string& path, const DesignStudyResult& result);

/// keys [{key, unit}], columns [{name, unit}], rows [{variant, values {key: value}, status,
/// results [...] or null}], failed, segments, unknowns, threads, cost (seconds per stage summed
/// over the variants and per variant, wall seconds), notes.
Json to_json(const DesignStudyResult& result);

}  // namespace emnet
