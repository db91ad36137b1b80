// CSV files of results: a header line, then one line of numbers per row.
//
// A header field with a comma, quote or line break is quoted, its quotes doubled (RFC 4180);
// numbers are written with %.12g (12 significant digits, enough for every printed result), a
// comma between them and "\n" after each line. The file is written completely or not at all
// (emnet/core/output_file.hpp): a failure leaves the previous file, if any, and is returned as
// a failed Status "<path>: <reason>", never thrown.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"

namespace emnet {

/// `text` as a CSV field: unchanged, or quoted when it holds a comma, quote, CR or LF.
std::string csv_field(const std::string& text);

/// The header, then `count` rows, row i filled by fill_row(i, row) (the row is cleared before);
/// the rows are formatted as they are written, not stored.
/// @return the failure "<path>: <reason>" when the file could not be written, else success
Status write_csv_rows(const std::string& path, const std::vector<std::string>& header,
                      std::size_t count,
                      const std::function<void(std::size_t, std::vector<double>&)>& fill_row);

/// The header, then one line per entry of `rows` (write_csv_rows over them).
Status write_csv(const std::string& path, const std::vector<std::string>& header,
                 const std::vector<std::vector<double>>& rows);

}  // namespace emnet
