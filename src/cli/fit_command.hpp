#pragma once
// The paper's analyses of a sweep's points on the command line: `fit` (a - c phi^b and 1 - p ln phi)
// and `averagings` (the paper's two averagings of per-medium points).

#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <string>

namespace softdrop::cli {

struct FitArgs {
  std::string db;  ///< sweep store ...
  std::int64_t sweep = 0;
  std::string points;            ///< ... or a CSV with columns porosity,tortuosity,standard_error
  std::string errors = "media";  ///< a sweep's points weighed by media_standard_error, or "droplets"
  std::string mean = "pooled";   ///< the porosity's mean over its droplets, or "per-medium" first
  std::string plot;              ///< T(phi) with error bars and both fits
  int size = 800;                ///< plot width (points)
  double dpi = 72;               ///< PNG pixels an inch
  std::string format = "table";
  std::string json_file;
};

struct AveragingArgs {
  std::string db = "sweep.db";
  std::int64_t sweep = 0;
  int group = 0;                  ///< points per group; 0: from the store (see default_group)
  std::string leftover = "drop";  ///< drop or keep (see Leftover)
  std::string csv, plot;
  int size = 800;   ///< plot width (points)
  double dpi = 72;  ///< PNG pixels an inch
};

void add_fit_commands(CLI::App& app, FitArgs& fit, AveragingArgs& averaging);
int run_fit(const FitArgs& args);
int run_averagings(const AveragingArgs& args);

}  // namespace softdrop::cli
