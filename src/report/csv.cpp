// CSV files of results (emnet/report/csv.hpp).
#include "emnet/report/csv.hpp"

#include <cstdio>

#include "emnet/core/output_file.hpp"

namespace emnet {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

Status write_csv_rows(const std::string& path, const std::vector<std::string>& header,
                      std::size_t count,
                      const std::function<void(std::size_t, std::vector<double>&)>& fill_row) {
  OutputFile out(path);
  std::string line;
  for (std::size_t k = 0; k < header.size(); ++k) line += (k ? "," : "") + csv_field(header[k]);
  out.write(line + "\n");
  char number[32];
  std::vector<double> row;
  for (std::size_t i = 0; i < count; ++i) {  // every row filled, as a caller may check it
    row.clear();
    fill_row(i, row);
    line.clear();
    for (std::size_t k = 0; k < row.size(); ++k) {
      std::snprintf(number, sizeof number, "%s%.12g", k ? "," : "", row[k]);
      line += number;
    }
    out.write(line + "\n");
  }
  return out.commit();
}

Status write_csv(const std::string& path, const std::vector<std::string>& header,
                 const std::vector<std::vector<double>>& rows) {
  return write_csv_rows(path, header, rows.size(),
                        [&](std::size_t i, std::vector<double>& row) { row = rows[i]; });
}

}  // namespace emnet
