#include "cli/options_diff.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace softdrop::cli {

std::vector<std::string> varying_options(const std::vector<std::string>& params) {
  std::vector<nlohmann::ordered_json> all;
  for (const std::string& p : params) all.push_back(nlohmann::ordered_json::parse(p));
  std::vector<std::string> keys;
  auto add = [&](const std::string& k) {
    if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  };
  for (const auto& j : all)
    for (const auto& [k, v] : j.items())
      for (const auto& other : all)
        if (!other.contains(k) || other[k] != v) add(k);
  return keys;
}

std::string options_text(const std::string& params, const std::vector<std::string>& keys) {
  const auto j = nlohmann::ordered_json::parse(params);
  std::string out;
  for (const std::string& k : keys) {
    if (!out.empty()) out += ' ';
    out += k + '=' + (!j.contains(k) ? "(none)" : j[k].is_string() ? j[k].get<std::string>() : j[k].dump());
  }
  return out;
}

}  // namespace softdrop::cli
