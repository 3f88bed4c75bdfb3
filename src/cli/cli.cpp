#include "cli/cli.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cli/common_options.hpp"
#include "cli/config_file.hpp"
#include "cli/file_roles.hpp"
#include "cli/mpi_job.hpp"
#include "cli/output.hpp"
#include "cli/suggest.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/store.hpp"
#include "softdrop/sweep.hpp"
#include "softdrop/version.hpp"

namespace softdrop::cli {
namespace {

// Errors are one line, whatever the library that raised them put in its message.
std::string one_line(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return message;
}

// --check goes one step beyond the run's own checks where it can: a generated non-overlapping or
// relaxed medium is generated as the run would, so a grain count or porosity that its placement
// cannot reach is reported now rather than when the run starts.
void check_placement(MediumOptions o) {
  if (o.kind == MediumKind::overlapping) return;
  try {
    (void)generate_medium(o);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
}

// Checks every option's values get before they are converted, since CLI11 converts without a
// word: an empty value to 0 (or ""; a path of "" means a temporary database to SQLite), and a whole
// number past the 64-bit range to the range's end. On the command line, in a config file and in
// each element of a comma-separated list.
void add_value_checks(CLI::App& command) {
  const CLI::Validator not_empty(
      [](std::string& value) { return value.empty() ? std::string("an empty value") : std::string(); }, "");
  const CLI::Validator in_range(
      [](std::string& value) {
        const char* begin = value.c_str();
        char* end = nullptr;
        errno = 0;
        (void)std::strtoll(begin, &end, 10);
        const bool whole = end != begin && *end == '\0';
        return whole && errno == ERANGE ? "'" + value + "' is out of range" : std::string();
      },
      "");
  for (CLI::Option* o : command.get_options()) {
    if (o->get_type_size_max() <= 0) continue;
    o->check(not_empty);
    if (o->get_type_name() == "INT") o->check(in_range);
  }
  for (CLI::App* sub : command.get_subcommands([](CLI::App*) { return true; })) add_value_checks(*sub);
}

// The checks of a command line as a whole, for the chosen command and its subcommand.
void check_command_line(const CLI::App& app, const std::vector<std::string>& words) {
  for (const CLI::App* a = &app; !a->get_subcommands().empty();) {
    a = a->get_subcommands().back();
    check_medium_file_alone(*a, words);
  }
  // A sweep's media take the porosities of --porosities and seeds derived from --seed: one
  // medium's porosity or seed on its command line would be ignored (a config file's are left alone).
  if (app.got_subcommand("sweep"))
    for (const char* unused : {"--porosity", "--medium-seed"})
      if (std::any_of(words.begin(), words.end(),
                      [&](const std::string& w) { return w == unused || w.rfind(std::string(unused) + "=", 0) == 0; }))
        throw std::invalid_argument(std::string(unused + 2) + ": not an option of sweep, whose media take " +
                                    (unused == std::string("--porosity") ? "--porosities" : "their seeds from --seed") +
                                    "; leave it out");
}

}  // namespace

Cli::Cli() {
  app.set_version_flag("--version", softdrop::kVersion);
  app.require_subcommand(1);
  // A later value overrides an earlier one, so scripts can append to a default command line.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.set_config("--config", "", "Read options from this TOML/INI file (keys: long option names)");
  app.config_formatter(std::make_shared<SubcommandConfig>(app));
  app.allow_config_extras(CLI::config_extras_mode::error);
  app.add_flag("--check", check_only_,
               "Check the options, the output folders, and that a generated non-overlapping medium can be "
               "placed (it is generated, which may take seconds), then exit without running or writing (exit 0: "
               "valid). It cannot know whether droplets will pass, or whether optimize finds a starting medium "
               "its droplet passes");
  simulate_cmd_ = add_simulate_command(app, simulate_);
  optimize_cmd_ = add_optimize_command(app, optimize_);
  history_cmd_ = add_history_command(app, history_);
  export_cmd_ = add_export_command(app, export_);
  add_sweep_command(app, sweep_);
  add_sweep_merge_command(app, sweep_merge_);
  add_sweep_report_command(app, sweep_report_);
  add_fit_commands(app, fit_, averagings_);
  render_cmd_ = add_render_command(app, render_);
  calibrate_cmd_ = add_calibrate_command(app, calibrate_);
  validate_cmd_ = add_validate_command(app, validate_);
  tortuosity_cmd_ = add_tortuosity_command(app, tortuosity_);
  columns_cmd_ = add_columns_command(app, columns_);
  add_value_checks(app);
}

void Cli::parse(int argc, const char* const* argv) {
  words_.assign(argv + 1, argv + argc);
  app.parse(argc, argv);
}

void Cli::check() {
  check_distinct_files(named_files(app));
  check_command_line(app, words_);
  if (simulate_cmd_->parsed()) {
    take_sweep_droplet(simulate_, *simulate_cmd_);
    check_simulate(simulate_);
    if (simulate_.medium.file.empty()) check_placement(simulate_.medium.options);
  }
  // A database the run would refuse (a missing or read-only folder, a foreign or damaged file) is
  // refused here too; the check reads it and writes nothing.
  if (optimize_cmd_->parsed()) {
    check_optimize(optimize_, *optimize_cmd_);
    if (optimize_.medium.file.empty() && optimize_.resume == 0) check_placement(optimize_.medium.options);
    check_database(optimize_.out.db);
  }
  if (app.got_subcommand("sweep")) {
    check_sweep(sweep_, *app.get_subcommand("sweep"));
    check_database(sweep_.db);
    for (int p = 0; p < static_cast<int>(sweep_.sweep.porosities.size()); ++p) {  // each porosity's first medium
      MediumOptions o = sweep_.sweep.medium;
      o.porosity = sweep_.sweep.porosities[static_cast<std::size_t>(p)];
      o.seed = sweep_medium_seed(sweep_.sweep, SweepUnit{p, 0});
      check_placement(o);
    }
  }
  if (render_cmd_->parsed() && !render_cmd_->get_subcommands().empty())
    check_render(render_, render_cmd_->get_subcommands().front()->get_name());
  if (calibrate_cmd_->parsed()) check_calibrate(calibrate_);
  if (validate_cmd_->parsed()) check_validate(validate_, *validate_cmd_);
  if (tortuosity_cmd_->parsed()) {
    check_tortuosity(tortuosity_);
    if (tortuosity_.medium.file.empty()) check_placement(tortuosity_.medium.options);
    // The medium as the run makes it, for the resolution it needs.
    const Medium medium = tortuosity_.medium.file.empty() ? generate_medium(tortuosity_.medium.options)
                                                          : load_medium_file(tortuosity_.medium);
    (void)check_resolution(medium, tortuosity_pixels(tortuosity_, medium));
  }
}

int Cli::run() {
  if (check_only_) {
    check();
    return 0;
  }
  // Before anything is read or written: no output may be a file the command reads or writes
  // under another name, and no option may be given that the command would ignore.
  check_distinct_files(named_files(app));
  check_command_line(app, words_);
  if (simulate_cmd_->parsed()) {
    take_sweep_droplet(simulate_, *simulate_cmd_);
    return run_simulate(simulate_);
  }
  if (optimize_cmd_->parsed()) return run_optimize(optimize_, *optimize_cmd_, host_);
  if (history_cmd_->parsed()) return run_history(history_);
  if (export_cmd_->parsed()) return run_export(export_);
  if (app.got_subcommand("sweep")) return run_sweep(sweep_, *app.get_subcommand("sweep"), host_);
  if (app.got_subcommand("sweep-merge")) return run_sweep_merge(sweep_merge_);
  if (app.got_subcommand("sweep-report")) return run_sweep_report(sweep_report_);
  if (app.got_subcommand("fit")) return run_fit(fit_);
  if (app.got_subcommand("averagings")) return run_averagings(averagings_);
  if (render_cmd_->parsed()) return run_render(render_, *render_cmd_);
  if (calibrate_cmd_->parsed()) return run_calibrate(calibrate_);
  if (validate_cmd_->parsed()) return run_validate(validate_, *validate_cmd_);
  if (tortuosity_cmd_->parsed()) return run_tortuosity(tortuosity_);
  if (columns_cmd_->parsed()) return run_columns(columns_);
  return 0;
}

std::string Cli::parse_error_line(const CLI::ParseError& error, int argc, const char* const* argv) const {
  const std::string correction = suggest_correction(app, argc, argv);
  return correction.empty() ? one_line(error.what()) : correction;
}

int main(int argc, char** argv) {
  remove_temp_files_on_signals();
  // Under mpirun (or srun) this process is one rank of a job. A build without MPI started as one
  // of several ranks says so; started alone it is the plain program.
  std::optional<Job> job;
  if (launched_by_mpi() && (built_with_mpi() || launched_ranks() > 1)) {
    try {
      job.emplace(&argc, &argv);
    } catch (const std::exception& e) {
      std::cerr << "softdrop: error: " << one_line(e.what()) << '\n';
      return 1;
    }
  }
  const bool speaks = !job || job->rank() == 0;  // the other ranks leave the messages to rank 0
  Cli cli;
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return speaks ? cli.app.exit(e) : 0;  // --help, --version
    if (speaks) std::cerr << "softdrop: error: " << cli.parse_error_line(e, argc, argv) << '\n';
    return 2;
  }
  if (job && job->size() > 1 && !cli.app.got_subcommand("sweep") && !cli.app.got_subcommand("optimize")) {
    if (speaks)
      std::cerr << "softdrop: error: only sweep and optimize --islands run across MPI ranks; run "
                << cli.app.get_subcommands().front()->get_name() << " without mpirun\n";
    return 2;
  }
  try {
    return cli.run();
  } catch (const std::exception& e) {
    if (!job || job->size() == 1) {
      std::cerr << "softdrop: error: " << one_line(e.what()) << '\n';
      return 1;
    }
    // The other ranks may be waiting for this one: the job ends. A bad option fails on every
    // rank alike, and rank 0 alone says so.
    const bool everywhere = dynamic_cast<const std::invalid_argument*>(&e) != nullptr;
    if (speaks || !everywhere) std::cerr << "softdrop: error: " << one_line(e.what()) << '\n';
    // The others give rank 0 time to say it and end the job: an abort from another rank first
    // could kill rank 0 before its line is out.
    if (!speaks && everywhere) std::this_thread::sleep_for(std::chrono::seconds(5));
    job->abort(1);
  }
}

}  // namespace softdrop::cli
