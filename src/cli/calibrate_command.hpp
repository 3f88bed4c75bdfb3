#pragma once
// `softdrop calibrate`: scans droplet parameters, runs a small sweep and area traces for each
// setting, and ranks the settings by their distance from the paper's results.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/common_options.hpp"
#include "studies/calibration.hpp"

namespace softdrop::cli {

struct CalibrateArgs {
  CalibrationOptions calibration;
  MediumArgs medium;
  std::vector<std::string> scans;     ///< "name=values", one per axis
  std::vector<std::string> settings;  ///< or explicit settings, "name=value name=value ..."
  bool skip_unstable = false;         ///< record unstable settings as refused instead of refusing the scan
  std::string csv, points, plot;      ///< output files
  int best = 3;                       ///< settings drawn in the plot
  int threads = 0;
  bool quiet = false;
  std::string format = "table";
};

CLI::App* add_calibrate_command(CLI::App& app, CalibrateArgs& args);
/// Checks the options and builds the settings, without running; throws std::invalid_argument
/// naming the bad parameter (an unstable setting included, unless --skip-unstable). `labels`, if
/// given, receives each setting's assignments.
std::vector<DropletParams> check_calibrate(CalibrateArgs& args, std::vector<std::string>* labels = nullptr);
int run_calibrate(CalibrateArgs& args);

}  // namespace softdrop::cli
