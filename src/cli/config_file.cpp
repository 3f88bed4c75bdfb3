#include "cli/config_file.hpp"

#include <iterator>
#include <sstream>
#include <stdexcept>
#include <toml++/toml.h>

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
  for (auto& item : found)
    if (item.parents.empty()) item.parents = chain;
  return found;
}

}  // namespace softdrop::cli
