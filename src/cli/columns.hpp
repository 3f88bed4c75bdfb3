#pragma once
// The names of everything softdrop writes: CSV columns, JSON keys, the database's views and the
// Python frames and results. One quantity has one name everywhere; `softdrop columns` prints the
// table and docs/files.md explains the rules it follows.

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace softdrop::cli {

struct ColumnName {
  const char* name;
  const char* unit;  ///< "1" dimensionless; length, time and mass in the model's units; "s" wall time
  const char* meaning;
};

/// A droplet parameter's column (and Python attribute): its long option name with '_' for '-'
/// (max-strain: max_strain), so that pandas can name it as an attribute.
std::string column_name(std::string option_key);

/// Every name, sorted. Droplet parameters (calibrate's columns) are named by their long option
/// with '_' for '-' and are not listed here: see is_column_name.
const std::vector<ColumnName>& column_names();

/// Whether `name` is in the table, or is a droplet parameter's column (calibrate writes them).
bool is_column_name(std::string_view name);

/// Throws std::logic_error naming the first of `names` that is not a column name: a writer that
/// would put a name outside the vocabulary into a file is a bug, caught by the tests that run it.
void check_column_names(const std::vector<std::string>& names);
/// The same for a CSV header line ("a,b,c").
void check_csv_header(std::string_view header);

struct ColumnsArgs {
  std::string format = "table";
  std::vector<std::string> names;  ///< only these (default: all)
};
CLI::App* add_columns_command(CLI::App& app, ColumnsArgs& a);
int run_columns(const ColumnsArgs& a);

}  // namespace softdrop::cli
