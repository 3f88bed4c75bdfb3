#pragma once
// "Did you mean": the nearest known option or command to a mistyped one.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace softdrop::cli {

/// For a command line the parser refused: "unknown option '--porosty' (did you mean --porosity?)"
/// or "unknown command 'simulat' (did you mean simulate?)" for the first unknown word that is close
/// (within a third of its length, at least 2 edits) to an option of the commands it follows or to a
/// command; for an unknown command with none close, the commands there are; for a command that
/// needs one of its own and was given none ("render"), those; "" when there is nothing to say, and
/// the parser's own message stands.
std::string suggest_correction(const CLI::App& app, int argc, const char* const* argv);

/// The long option name (without dashes) of `command` or of the program `app` nearest to `name`,
/// by the same rule; "" if none is close. For keys of config files, which name options so.
std::string nearest_option(const CLI::App& app, const CLI::App& command, const std::string& name);

/// The nearest of `names` to `word` by the same rule; "" if none is close.
std::string nearest_name(const std::string& word, const std::vector<std::string>& names);

}  // namespace softdrop::cli
