#include "keyword_values.hpp"

#include <algorithm>
#include <stdexcept>

#include "arguments.hpp"
#include "cli/config_file.hpp"
#include "cli/suggest.hpp"

namespace softdrop::python {
namespace {

// A keyword's library name: '_' as '-', and a trailing '_' (lambda_, Python's keyword) dropped.
std::string library_name(std::string keyword) {
  while (!keyword.empty() && keyword.back() == '_') keyword.pop_back();
  std::replace(keyword.begin(), keyword.end(), '_', '-');
  return keyword;
}

// `value` read as the type of `like`, the default of the option `option` (a seed: from 0 to
// 2^64 - 1); errors name `name`.
nlohmann::json typed_value(py::handle value, const nlohmann::json& like, const std::string& option, const char* name) {
  if (like.is_boolean()) return bool_arg(value, name);
  if (like.is_number_integer() && option.size() >= 4 && option.compare(option.size() - 4, 4, "seed") == 0)
    return seed_arg(value, name);
  if (like.is_number_integer()) return whole_arg(value, name);
  if (like.is_number_float()) return real_arg(value, name);
  if (like.is_array()) {
    const std::vector<double> reals = reals_arg(value, name);
    if (reals.empty()) throw py::value_error(std::string(name) + ": an empty list");
    return reals;
  }
  // A string: a str, or a file name as os.PathLike.
  if (!PyUnicode_Check(value.ptr()) && PyObject_HasAttrString(value.ptr(), "__fspath__"))
    return path_arg(value, name).string();
  return text_arg(value, name);
}

}  // namespace

py::object json_to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

std::string keyword_of(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name == "lambda" ? "lambda_" : name;
}

std::vector<std::string> read_keywords(const std::string& command, const py::dict& keywords, nlohmann::json* values,
                                       const std::map<std::string, CallOption>& options,
                                       const std::function<bool(const std::string&)>& shapes_a_medium) {
  std::vector<std::string> given;
  const auto set = [&](const std::string& name, py::handle value, const std::string& what) {
    if (const auto o = options.find(name); o != options.end()) {
      o->second(value, what.c_str());
    } else {
      (*values)[name] = typed_value(value, values->at(name), name, what.c_str());
      if (std::find(given.begin(), given.end(), name) == given.end()) given.push_back(name);
    }
  };
  const auto known = [&](const std::string& name) { return options.count(name) > 0 || values->contains(name); };
  std::vector<std::string> names;
  for (const auto& [name, value] : values->items()) names.push_back(name);
  for (const auto& [name, option] : options) names.push_back(name);

  if (keywords.contains("config") && !keywords["config"].is_none()) {
    const std::string file = path_arg(keywords["config"], "config").string();
    for (const auto& [key, value] : cli::config_values(file, command)) {
      const std::string where = "config file '" + file + "': " + key;
      if (key == "config" || !known(key)) {
        if (key != "config" && shapes_a_medium(key)) continue;
        const std::string near = cli::nearest_name(key, names);
        throw std::invalid_argument(where + ": " + command + " has no option --" + key +
                                    (near.empty() ? "" : " (did you mean " + near + "?)"));
      }
      set(key, json_to_python(value), where);
    }
  }
  for (const auto& [k, value] : keywords) {
    const std::string keyword = py::str(k);
    if (keyword == "config" || value.is_none()) continue;  // None: the option's default, as if not given
    const std::string name = library_name(keyword);
    if (!known(name)) {
      const std::string near = cli::nearest_name(name, names);
      throw py::type_error(command + "() got an unexpected keyword argument '" + keyword + "'" +
                           (near.empty() ? "" : " (did you mean " + keyword_of(near) + "?)"));
    }
    set(name, value, keyword);
  }
  return given;
}

std::vector<std::string> keyword_names(const nlohmann::json& values, const std::map<std::string, CallOption>& options) {
  std::vector<std::string> names;
  for (const auto& [name, value] : values.items()) names.push_back(keyword_of(name));
  for (const auto& [name, option] : options) names.push_back(keyword_of(name));
  return names;
}

}  // namespace softdrop::python
