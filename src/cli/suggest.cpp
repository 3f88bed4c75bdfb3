#include "cli/suggest.hpp"

#include <algorithm>
#include <vector>

namespace softdrop::cli {
namespace {

// Levenshtein distance (insertions, deletions, substitutions), by one row.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The long option names of `app` and of its option groups.
void long_names(const CLI::App& app, std::vector<std::string>* out) {
  for (const CLI::Option* o : app.get_options())
    for (const std::string& n : o->get_lnames()) out->push_back(n);
  for (const CLI::App* group : app.get_subcommands([](const CLI::App* a) { return a->get_name().empty(); }))
    long_names(*group, out);
}

// The nearest of `names` to `word`, or "" if none is close enough to be what was meant.
std::string nearest(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& n : names)
    if (const std::size_t d = edit_distance(word, n); d < best_distance) best_distance = d, best = n;
  return best;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  return nearest(word, names);
}

std::string nearest_option(const CLI::App& app, const CLI::App& command, const std::string& name) {
  std::vector<std::string> names;
  long_names(command, &names);
  if (&command != &app) long_names(app, &names);
  return nearest(name, names);
}

std::string suggest_correction(const CLI::App& app, int argc, const char* const* argv) {
  std::vector<const CLI::App*> chain{&app};  // the commands named so far
  bool options_seen = false;                 // after an option, a plain word may be its value
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.rfind("--", 0) == 0 && word.size() > 2) {
      const std::string name =
          word.substr(2, word.find('=') == std::string::npos ? std::string::npos : word.find('=') - 2);
      options_seen = true;
      bool known = false;
      std::vector<std::string> names;
      for (const CLI::App* a : chain) {
        known = known || a->get_option_no_throw("--" + name) != nullptr;
        long_names(*a, &names);
      }
      if (known) continue;
      const std::string near = nearest(name, names);
      return near.empty() ? "" : "unknown option '--" + name + "' (did you mean --" + near + "?)";
    }
    if (word.empty() || word[0] == '-') continue;
    const CLI::App* here = chain.back();
    const auto commands = here->get_subcommands([](const CLI::App* a) { return !a->get_name().empty(); });
    if (commands.empty()) continue;
    const auto match =
        std::find_if(commands.begin(), commands.end(), [&](const CLI::App* a) { return a->check_name(word); });
    if (match != commands.end()) {
      chain.push_back(*match);
      options_seen = false;
      continue;
    }
    if (options_seen) continue;
    std::vector<std::string> names;
    for (const CLI::App* a : commands) names.push_back(a->get_name());
    const std::string near = nearest(word, names);
    const std::string of = chain.size() > 1 ? " of " + here->get_name() : "";
    return near.empty() ? "unknown command '" + word + "'" + of + " (one of " + joined(names) + ")"
                        : "unknown command '" + word + "'" + of + " (did you mean " + near + "?)";
  }
  // A command that needs one of its own, given none: name them.
  const CLI::App* last = chain.back();
  if (last->get_require_subcommand_min() > 0 && !options_seen) {
    std::vector<std::string> names;
    for (const CLI::App* a : last->get_subcommands([](const CLI::App* a) { return !a->get_name().empty(); }))
      names.push_back(a->get_name());
    if (!names.empty())
      return (chain.size() > 1 ? last->get_name() : std::string("softdrop")) + " needs a command: one of " +
             joined(names);
  }
  return "";
}

}  // namespace softdrop::cli
