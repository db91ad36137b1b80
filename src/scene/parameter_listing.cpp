// The parameter table as a plain-text or Markdown table; see emnet/scene/parameter_listing.hpp.
#include "emnet/scene/parameter_listing.hpp"

#include <algorithm>
#include <sstream>

#include "emnet/scene/parameters.hpp"

namespace emnet {

std::vector<ParameterListingRow> parameter_listing() {
  std::vector<ParameterListingRow> rows;
  for (const ParameterInfo& info : parameter_table()) {
    ParameterListingRow row;
    row.key = info.key();
    row.kind = parameter_kind_name(info.kind);
    row.unit = info.unit();
    row.default_text = parameter_default_text(info);
    row.range = parameter_range_text(info);
    row.used_by = info.used_by;
    row.meaning = info.meaning;
    row.required = info.required;
    row.sensitivity = info.sensitivity;
    rows.push_back(std::move(row));
  }
  return rows;
}

namespace {

// `text` cut into lines of at most `width` characters at spaces (a longer word stays whole).
std::vector<std::string> wrapped(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

std::string table_of(const std::string& key) {
  return key.substr(0, key.find_first_of(".["));
}

}  // namespace

std::string parameter_listing_text() {
  const std::vector<ParameterListingRow> rows = parameter_listing();
  const std::vector<std::string> headers = {"KEY",   "UNIT",    "DEFAULT",
                                            "RANGE", "USED BY", "MEANING"};
  std::size_t key_width = headers[0].size();
  for (const ParameterListingRow& row : rows) key_width = std::max(key_width, row.key.size());
  const std::vector<std::size_t> widths = {key_width, 12, 24, 30, 20, 44};
  std::ostringstream out;
  // Each column starts where the widths before it end (a word longer than its column pushes the
  // rest of that line right, never the next line).
  auto write_line = [&](const std::vector<std::string>& cells) {
    std::string line;
    std::size_t column_start = 0;
    for (std::size_t column = 0; column < cells.size(); ++column) {
      if (line.size() < column_start) line.append(column_start - line.size(), ' ');
      line += cells[column];
      column_start += widths[column] + 2;
      if (line.size() + 1 > column_start && column + 1 < cells.size()) line += ' ';
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << "\n";
  };
  write_line(headers);
  std::string previous_table;
  for (const ParameterListingRow& row : rows) {
    const std::string table = table_of(row.key);
    if (!previous_table.empty() && table != previous_table) out << "\n";
    previous_table = table;
    const std::vector<std::string> cells = {row.key,   row.unit,    row.default_text,
                                            row.range, row.used_by, row.meaning};
    std::vector<std::vector<std::string>> columns;
    std::size_t height = 0;
    for (std::size_t column = 0; column < cells.size(); ++column) {
      columns.push_back(column == 0 ? std::vector<std::string>{cells[0]}
                                    : wrapped(cells[column], widths[column]));
      height = std::max(height, columns.back().size());
    }
    for (std::size_t line = 0; line < height; ++line) {
      std::vector<std::string> parts;
      for (const auto& column : columns) parts.push_back(line < column.size() ? column[line] : "");
      write_line(parts);
    }
  }
  return out.str();
}

std::string parameter_listing_markdown() {
  auto cell = [](const std::string& text) {
    std::string escaped;
    for (char character : text) {
      if (character == '|') escaped += '\\';
      escaped += character;
    }
    return escaped;
  };
  std::ostringstream out;
  out << "| key | unit | default | range | used by | meaning |\n";
  out << "|---|---|---|---|---|---|\n";
  for (const ParameterListingRow& row : parameter_listing()) {
    out << "| `" << row.key << "` | " << cell(row.unit) << " | " << cell(row.default_text) << " | "
        << cell(row.range) << " | " << cell(row.used_by) << " | " << cell(row.meaning) << " |\n";
  }
  return out.str();
}

}  // namespace emnet
