#pragma once
// The tests' CSV reader: what pandas' read_csv takes as is. The first line is the header, every
// other line a row with as many fields; fields may be quoted ("a, b" and "" for a quote). No
// comment lines, no special cases: a file it refuses is not a plain CSV.
#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace softdrop::test {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  std::size_t column(const std::string& name) const {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end()) throw std::runtime_error("no column " + name);
    return static_cast<std::size_t>(at - header.begin());
  }
  const std::string& cell(std::size_t row, const std::string& name) const { return rows.at(row).at(column(name)); }
  double number(std::size_t row, const std::string& name) const { return std::stod(cell(row, name)); }
};

inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      fields.back() += '"', ++i;
    else if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      fields.emplace_back();
    else
      fields.back() += c;
  }
  if (quoted) throw std::runtime_error("unterminated quote: " + line);
  return fields;
}

/// Reads `path`; throws std::runtime_error saying what is not plain.
inline CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  CsvTable t;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#')
      throw std::runtime_error(path + " line " + std::to_string(number) + ": not a header or a row: '" + line + "'");
    auto fields = csv_fields(line);
    if (number == 1) {
      t.header = std::move(fields);
      continue;
    }
    if (fields.size() != t.header.size())
      throw std::runtime_error(path + " line " + std::to_string(number) + ": " + std::to_string(fields.size()) +
                               " fields, the header has " + std::to_string(t.header.size()));
    t.rows.push_back(std::move(fields));
  }
  if (t.header.empty()) throw std::runtime_error(path + ": empty");
  return t;
}

}  // namespace softdrop::test
