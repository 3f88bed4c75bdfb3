#include "cli/file_roles.hpp"

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <system_error>

namespace softdrop::cli {
namespace {

namespace fs = std::filesystem;

// The options that name files, by name. --points is an input of fit and an output of calibrate;
// --db is written by the commands that create or extend a store, read by the others.
constexpr const char* kOutputs[] = {"--json",  "--csv",       "--runs",        "--trace",
                                    "--paths", "--snapshots", "--save-medium", "--simulate-config",
                                    "--plot",  "--curve",     "--output"};
constexpr const char* kInputs[] = {"--medium", "--config", "--from-sweep"};

auto named_as(const std::string& name) {
  return [&name](const char* n) { return name == n; };
}

// The chain of chosen commands from the program down: softdrop, render, medium.
std::vector<const CLI::App*> chosen(const CLI::App& app) {
  std::vector<const CLI::App*> chain{&app};
  for (const CLI::App* a = &app;;) {
    const auto subs = a->get_subcommands();
    if (subs.empty()) break;
    a = subs.back();
    chain.push_back(a);
  }
  return chain;
}

// The values an option holds: those given (command line or config file), else its default.
std::vector<std::string> values_of(const CLI::Option& o) {
  if (o.count() > 0) return o.results();
  if (!o.get_default_str().empty()) return {o.get_default_str()};
  return {};
}

std::string canonical(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal().string() : p.string();
}

}  // namespace

void options_of(const CLI::App& command, std::vector<const CLI::Option*>* out) {
  for (const CLI::Option* o : command.get_options()) out->push_back(o);
  for (const CLI::App* group : command.get_subcommands([](const CLI::App* s) { return s->get_name().empty(); }))
    options_of(*group, out);
}

std::vector<NamedFile> named_files(const CLI::App& app) {
  const auto chain = chosen(app);
  const std::string command = chain.size() > 1 ? chain[1]->get_name() : "";
  std::vector<NamedFile> files;
  std::vector<const CLI::Option*> options;
  for (const CLI::App* a : chain) options_of(*a, &options);
  for (const CLI::Option* o : options) {
    const std::string name = o->get_name();
    NamedFile f{name, "", false, false};
    if (name == "--db") {  // the commands that create or extend a store write it
      f.database = true;
      f.written = command == "optimize" || command == "sweep" || command == "validate";
    } else if (name == "--into") {  // sweep-merge's output store
      f.database = f.written = true;
    } else if (name == "inputs") {  // sweep-merge's input stores
      f.database = true;
    } else if (name == "--points") {
      f.written = command == "calibrate";
    } else if (std::any_of(std::begin(kOutputs), std::end(kOutputs), named_as(name))) {
      f.written = true;
    } else if (std::none_of(std::begin(kInputs), std::end(kInputs), named_as(name))) {
      continue;
    }
    for (const std::string& path : values_of(*o)) files.push_back({name, path, f.written, f.database});
  }
  return files;
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ea, eb;
  const bool a_exists = fs::exists(a, ea), b_exists = fs::exists(b, eb);
  if (a_exists && b_exists) {
    std::error_code ec;
    return fs::equivalent(a, b, ec);
  }
  if (a_exists != b_exists) return false;
  return canonical(a) == canonical(b);
}

void check_distinct_files(std::vector<NamedFile> files) {
  // A clash is named by the plain output in it, not by the database it would destroy.
  std::stable_partition(files.begin(), files.end(), [](const NamedFile& f) { return !f.database; });
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < files.size(); ++j) {
      const NamedFile &out = files[i], &other = files[j];
      if (i == j || !out.written) continue;
      if (j < i && other.written) continue;  // each pair of outputs once
      std::vector<std::string> aliases{other.path};
      if (other.database)
        for (const char* side : {"-wal", "-shm", "-journal"}) aliases.push_back(other.path + side);
      for (const std::string& alias : aliases)
        if (same_file(out.path, alias)) {
          const std::string what = alias == other.path ? other.option + " '" + other.path + "'"
                                                       : "the side file of " + other.option + " '" + other.path + "'";
          throw std::invalid_argument(out.option + " '" + out.path + "': the same file as " + what +
                                      "; writing it would destroy that file (name another file)");
        }
    }
}

}  // namespace softdrop::cli
