// softdrop: the command-line program. Every failure ends with one line on stderr and exit code 1
// (bad input found while running) or 2 (the command line itself is wrong).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "cli/history_command.hpp"
#include "cli/optimize_command.hpp"
#include "cli/render_command.hpp"
#include "cli/simulate_command.hpp"
#include "cli/sweep_command.hpp"
#include "softdrop/version.hpp"

namespace {
// Reads a TOML/INI file whose plain keys (`porosity = 0.8`) are the long options of the
// subcommand that was chosen, so a config file looks like the command line without dashes.
class SubcommandConfig : public CLI::ConfigTOML {
 public:
  explicit SubcommandConfig(const CLI::App& app) : app_(app) {}
  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override {
    auto parsed = CLI::ConfigTOML::from_config(input);
    // The chain of chosen subcommands, e.g. render -> medium.
    std::vector<std::string> chain;
    for (const CLI::App* a = &app_; !a->get_subcommands().empty();) {
      a = a->get_subcommands().back();
      chain.push_back(a->get_name());
    }
    for (auto& item : parsed)
      if (item.parents.empty()) item.parents = chain;
    return parsed;
  }

 private:
  const CLI::App& app_;
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"softdrop: soft-body droplets pushed through porous media of disc grains"};
  app.set_version_flag("--version", softdrop::kVersion);
  app.require_subcommand(1);
  // A later value overrides an earlier one, so scripts can append to a default command line.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.set_config("--config", "", "Read options from this TOML/INI file (keys: long option names)");
  app.config_formatter(std::make_shared<SubcommandConfig>(app));
  app.allow_config_extras(CLI::config_extras_mode::error);
  softdrop::cli::SimulateArgs simulate;
  CLI::App* simulate_cmd = softdrop::cli::add_simulate_command(app, simulate);
  softdrop::cli::OptimizeArgs optimize;
  CLI::App* optimize_cmd = softdrop::cli::add_optimize_command(app, optimize);
  softdrop::cli::HistoryArgs history;
  CLI::App* history_cmd = softdrop::cli::add_history_command(app, history);
  softdrop::cli::ExportArgs export_args;
  CLI::App* export_cmd = softdrop::cli::add_export_command(app, export_args);
  softdrop::cli::SweepArgs sweep;
  softdrop::cli::SweepMergeArgs sweep_merge;
  softdrop::cli::SweepReportArgs sweep_report;
  softdrop::cli::FitArgs fit;
  softdrop::cli::AveragingArgs averagings;
  softdrop::cli::add_study_commands(app, sweep, sweep_merge, sweep_report, fit, averagings);
  softdrop::cli::RenderArgs render;
  CLI::App* render_cmd = softdrop::cli::add_render_command(app, render);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::string message = e.what();
    for (char& c : message)
      if (c == '\n') c = ' ';
    std::cerr << "softdrop: error: " << message << '\n';
    return 2;
  }
  try {
    if (simulate_cmd->parsed()) return softdrop::cli::run_simulate(simulate);
    if (optimize_cmd->parsed()) return softdrop::cli::run_optimize(optimize, *optimize_cmd);
    if (history_cmd->parsed()) return softdrop::cli::run_history(history);
    if (export_cmd->parsed()) return softdrop::cli::run_export(export_args);
    if (app.got_subcommand("sweep")) return softdrop::cli::run_sweep(sweep, *app.get_subcommand("sweep"));
    if (app.got_subcommand("sweep-merge")) return softdrop::cli::run_sweep_merge(sweep_merge);
    if (app.got_subcommand("sweep-report")) return softdrop::cli::run_sweep_report(sweep_report);
    if (app.got_subcommand("fit")) return softdrop::cli::run_fit(fit);
    if (app.got_subcommand("averagings")) return softdrop::cli::run_averagings(averagings);
    if (render_cmd->parsed()) return softdrop::cli::run_render(render, *render_cmd);
  } catch (const std::exception& e) {
    std::cerr << "softdrop: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
