#pragma once
// The whole command line of softdrop: every subcommand's options, parsing, checking and running.
// main() is a thin shell around it, and the fuzz targets drive the same object.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/calibrate_command.hpp"
#include "cli/columns.hpp"
#include "cli/fit_command.hpp"
#include "cli/history_command.hpp"
#include "cli/host.hpp"
#include "cli/optimize_command.hpp"
#include "cli/render_command.hpp"
#include "cli/simulate_command.hpp"
#include "cli/sweep_command.hpp"
#include "cli/sweep_merge_command.hpp"
#include "cli/sweep_report_command.hpp"
#include "cli/tortuosity_command.hpp"
#include "cli/validate_command.hpp"

namespace softdrop::cli {

class Cli {
 public:
  Cli();
  Cli(const Cli&) = delete;
  Cli& operator=(const Cli&) = delete;

  /// Parses the command line (argv[0] is the program name); throws CLI::ParseError.
  void parse(int argc, const char* const* argv);
  /// Checks the chosen command's options without running it or touching its files; throws
  /// std::invalid_argument naming the bad parameter. Commands whose options are only files and
  /// ids (history, export, sweep-merge, sweep-report, fit, averagings) check them when run.
  void check();
  /// Runs the chosen command (after check(), or only check() with --check); returns the exit code.
  int run();
  /// Runs optimize and sweep for a host program (see Host) instead of a shell; the other
  /// commands ignore it. The host must outlive run().
  void set_host(Host* host) { host_ = host; }
  /// The one line the program prints for a command line the parser refused (without the
  /// "softdrop: error: " prefix): the nearest known option or command when there is one.
  std::string parse_error_line(const CLI::ParseError& error, int argc, const char* const* argv) const;

  CLI::App app{"softdrop: soft-body droplets pushed through porous media of disc grains"};

 private:
  bool check_only_ = false;
  std::vector<std::string> words_;  ///< the command line as parsed, to tell its options from a config file's
  Host* host_ = nullptr;
  SimulateArgs simulate_;
  OptimizeArgs optimize_;
  HistoryArgs history_;
  ExportArgs export_;
  SweepArgs sweep_;
  SweepMergeArgs sweep_merge_;
  SweepReportArgs sweep_report_;
  FitArgs fit_;
  AveragingArgs averagings_;
  RenderArgs render_;
  CalibrateArgs calibrate_;
  ValidateArgs validate_;
  TortuosityArgs tortuosity_;
  ColumnsArgs columns_;
  CLI::App* simulate_cmd_ = nullptr;
  CLI::App* optimize_cmd_ = nullptr;
  CLI::App* history_cmd_ = nullptr;
  CLI::App* export_cmd_ = nullptr;
  CLI::App* render_cmd_ = nullptr;
  CLI::App* calibrate_cmd_ = nullptr;
  CLI::App* validate_cmd_ = nullptr;
  CLI::App* tortuosity_cmd_ = nullptr;
  CLI::App* columns_cmd_ = nullptr;
};

/// The whole program: parses, runs, and turns every error into one line on stderr. Returns the
/// exit code: 0, 1 (bad input found while running), 2 (the command line is wrong), or what the
/// command returns (130 or 143 after a signal).
int main(int argc, char** argv);

}  // namespace softdrop::cli
