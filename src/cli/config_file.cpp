#include "cli/config_file.hpp"

#include <toml++/toml.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "cli/suggest.hpp"
#include "util/validation.hpp"

namespace softdrop::cli {
namespace {

// A scalar TOML value as the command line would spell it (numbers in their shortest exact form).
std::string spelled(const toml::node& v, const std::string& key) {
  if (const auto* s = v.as_string()) return s->get();
  if (const auto* i = v.as_integer()) return std::to_string(i->get());
  if (const auto* d = v.as_floating_point()) return detail::num(d->get());
  if (const auto* b = v.as_boolean()) return b->get() ? "true" : "false";
  throw CLI::ConversionError("config key '" + key + "': expected a string, number, boolean or array of them");
}

void collect(const toml::table& table, std::vector<std::string> parents, std::vector<CLI::ConfigItem>* out) {
  for (const auto& [k, v] : table) {
    const std::string key(k.str());
    if (const auto* sub = v.as_table()) {
      auto deeper = parents;
      deeper.push_back(key);
      collect(*sub, deeper, out);
      continue;
    }
    CLI::ConfigItem item;
    item.parents = parents;
    item.name = key;
    if (const auto* array = v.as_array())
      for (const toml::node& e : *array) item.inputs.push_back(spelled(e, key));
    else
      item.inputs.push_back(spelled(v, key));
    out->push_back(std::move(item));
  }
}

}  // namespace

// What the command line would refuse or misread is refused here, naming the file and the key:
// an empty array (it would hand the parser an option without a value), an array for an option
// that takes one value (the parser would keep its last element), and a key no option has.
bool SubcommandConfig::check_item(const CLI::ConfigItem& item, const std::string& file) const {
  const std::string where = "config file '" + file + "': " + item.name;
  if (item.inputs.empty())
    throw CLI::ConversionError(where + " = []: an empty array (give a value, or leave the key out)");
  const CLI::App* command = &app_;
  for (const std::string& parent : item.parents) {
    const auto named = command->get_subcommands([&](const CLI::App* sub) { return sub->get_name() == parent; });
    if (named.empty()) return true;  // not a command's table: the parser reports it
    command = named.front();
  }
  const CLI::Option* option = command->get_option_no_throw("--" + item.name);
  if (option == nullptr) option = app_.get_option_no_throw("--" + item.name);  // program-level options
  if (option == nullptr && shapes_a_medium(app_, item.name)) return false;
  if (option == nullptr) {
    std::string path;
    for (const std::string& parent : item.parents) path += parent + " ";
    const std::string near = nearest_option(app_, *command, item.name);
    throw CLI::ConversionError(where + ": " + (path.empty() ? std::string("softdrop ") : path) + "has no option --" +
                               item.name + (near.empty() ? "" : " (did you mean " + near + "?)"));
  }
  if (item.inputs.size() > 1 && option->get_items_expected_max() <= 1)
    throw CLI::ConversionError(where + ": --" + item.name + " takes one value, not an array of " +
                               std::to_string(item.inputs.size()));
  return true;
}

// The installed droplet configs name the grains their droplet was calibrated among (r-min, r-max),
// for the commands that generate media; a command that takes no medium options (validate, which
// reads its medium) leaves such keys alone, as it does a medium option on the command line.
bool shapes_a_medium(const CLI::App& app, const std::string& key) {
  const auto simulate = app.get_subcommands([](const CLI::App* s) { return s->get_name() == "simulate"; });
  if (simulate.empty()) return false;
  for (const CLI::App* group : simulate.front()->get_subcommands(
           [](const CLI::App* s) { return s->get_name().empty() && s->get_group() == "Medium"; }))
    if (group->get_option_no_throw("--" + key) != nullptr) return true;
  return false;
}

std::vector<CLI::ConfigItem> SubcommandConfig::from_config(std::istream& input) const {
  // The chain of chosen subcommands, e.g. render -> medium: the commands plain keys belong to.
  std::vector<std::string> chain;
  for (const CLI::App* a = &app_; !a->get_subcommands().empty();) {
    a = a->get_subcommands().back();
    chain.push_back(a->get_name());
  }
  const CLI::Option* file = app_.get_option_no_throw("--config");
  const std::string name = file && file->count() ? file->as<std::string>() : std::string("config");
  std::vector<CLI::ConfigItem> found;
  if (name.size() >= 4 && name.compare(name.size() - 4, 4, ".ini") == 0) {
    found = CLI::ConfigTOML::from_config(input);
  } else {
    const std::string text((std::istreambuf_iterator<char>(input)), std::istreambuf_iterator<char>());
    try {
      collect(toml::parse(text, name), {}, &found);
    } catch (const toml::parse_error& e) {
      std::ostringstream where;
      where << "config file '" << name << "' line " << e.source().begin.line << ", column " << e.source().begin.column
            << ": " << e.description() << " (not TOML; name the file .ini for an INI file)";
      throw CLI::ConversionError(where.str());
    }
  }
  // A key of the command's own table is more specific than a top-level key, which TOML puts
  // before every table, so it is the later value and wins. The parser keeps the first value an
  // option gets from a file, so the tables' keys go first.
  std::vector<CLI::ConfigItem> kept, top_level;
  for (auto& item : found) {
    const bool top = item.parents.empty();
    if (top) item.parents = chain;
    if (check_item(item, name)) (top ? top_level : kept).push_back(std::move(item));
  }
  kept.insert(kept.end(), std::make_move_iterator(top_level.begin()), std::make_move_iterator(top_level.end()));
  return kept;
}

namespace {
nlohmann::json json_value(const toml::node& v, const std::string& where) {
  if (const auto* s = v.as_string()) return s->get();
  if (const auto* i = v.as_integer()) return i->get();
  if (const auto* d = v.as_floating_point()) return d->get();
  if (const auto* b = v.as_boolean()) return b->get();
  if (const auto* array = v.as_array()) {
    if (array->empty())
      throw std::invalid_argument(where + " = []: an empty array (give a value, or leave the key out)");
    nlohmann::json out = nlohmann::json::array();
    for (const toml::node& e : *array) {
      if (e.is_array() || e.is_table()) throw std::invalid_argument(where + ": an array of arrays or tables");
      out.push_back(json_value(e, where));
    }
    return out;
  }
  throw std::invalid_argument(where + ": expected a string, number, boolean or array of them");
}
}  // namespace

std::vector<std::pair<std::string, nlohmann::json>> config_values(const std::string& file, const std::string& command) {
  std::ifstream in(file);
  if (!in) throw std::invalid_argument("config file '" + file + "': cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "config file '" << file << "' line " << e.source().begin.line << ", column " << e.source().begin.column
          << ": " << e.description() << " (not TOML)";
    throw std::invalid_argument(where.str());
  }
  std::vector<std::pair<std::string, nlohmann::json>> out;
  for (const auto& [k, v] : root)
    if (!v.is_table())
      out.emplace_back(std::string(k.str()), json_value(v, "config file '" + file + "': " + std::string(k.str())));
  if (const toml::table* own = root[command].as_table())
    for (const auto& [k, v] : *own)
      if (!v.is_table())
        out.emplace_back(std::string(k.str()), json_value(v, "config file '" + file + "': " + std::string(k.str())));
  return out;
}

}  // namespace softdrop::cli
