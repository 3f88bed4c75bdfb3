#pragma once
// What sets stored runs or sweeps apart: the options (keys of their parameter JSON) whose values
// differ, shown instead of whole JSON lines.
#include <string>
#include <vector>

namespace softdrop::cli {

/// The keys of `params` (JSON objects, one a record) whose values are not the same in all of them,
/// in the order of the first; a key missing from one counts as differing.
std::vector<std::string> varying_options(const std::vector<std::string>& params);
/// "key=value key=value" for `keys` of the JSON object `params` (values as JSON, strings bare).
std::string options_text(const std::string& params, const std::vector<std::string>& keys);

}  // namespace softdrop::cli
