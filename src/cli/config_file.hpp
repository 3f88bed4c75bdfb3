#pragma once
// --config files: TOML read by a real TOML parser (toml++), handed to the command-line parser as
// the options they name.
#include <CLI/CLI.hpp>
#include <istream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace softdrop::cli {

/// Reads a TOML file whose plain keys (`porosity = 0.8`) are the long options of the subcommand
/// that was chosen, so a config file looks like the command line without dashes; keys under a
/// table ([sweep]) belong to the command of that name. Strings, numbers, booleans and arrays of
/// them are values; a quoted "#ff0000" is a string. A file that is not TOML gets one error naming
/// its line and column; a file ending in .ini is read as INI instead (CLI11's reader). A key no
/// option of its command has, an empty array, or an array for an option of one value is refused
/// with a line naming the file and the key.
class SubcommandConfig : public CLI::ConfigTOML {
 public:
  explicit SubcommandConfig(const CLI::App& app) : app_(app) {}
  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override;

 private:
  /// Throws naming the file and key if the item is refused; false: leave it out (a medium's key
  /// for a command without medium options).
  bool check_item(const CLI::ConfigItem& item, const std::string& file) const;
  const CLI::App& app_;
};

/// Whether a config file's `key` is an option that shapes a generated medium (one of simulate's
/// medium options in the program `app`): a command that does not take it leaves it alone, where
/// another unknown key is refused.
bool shapes_a_medium(const CLI::App& app, const std::string& key);

/// The values a TOML config file gives the command `command`, for a host that takes options as
/// named values rather than a command line (the Python module): its plain keys, then those of its
/// [command] table, which win; each a string, number, boolean or array of them, as JSON. Throws
/// std::invalid_argument naming the file (and line and column) if it cannot be read or is not
/// TOML, or naming the key for a value of another kind or an empty array.
std::vector<std::pair<std::string, nlohmann::json>> config_values(const std::string& file, const std::string& command);

}  // namespace softdrop::cli
