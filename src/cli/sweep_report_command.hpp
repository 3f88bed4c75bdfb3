#pragma once
// `softdrop sweep-report`: a sweep's points from its store (sweep_report_command.cpp), and what the
// other readers of a sweep store share with it: the choice of a sweep, and the points' table that
// `sweep` prints when it ends.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/output.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {
class SweepStore;
}

namespace softdrop::cli {

struct SweepReportArgs {
  std::string db = "sweep.db";
  std::int64_t sweep = 0;        ///< 0: the only one
  bool media = false;            ///< per-medium rows instead of per-porosity points
  bool second_droplets = false;  ///< a sweep of pairs: the points of the second droplets
  std::string format = "table";
};

void add_sweep_report_command(CLI::App& app, SweepReportArgs& args);
int run_sweep_report(const SweepReportArgs& args);
/// The sweep `id` of the store, or its only sweep when id is 0; throws std::invalid_argument
/// naming the file when it holds none or several. A sweep that holds fewer media than it has is
/// warned of on stderr: its readers' figures are of part of it.
std::int64_t pick_sweep(SweepStore& store, std::int64_t id, const std::string& db);
/// The per-porosity points as a table, with the columns of sweep-report.
Table points_table(const std::vector<SweepPoint>& points);

}  // namespace softdrop::cli
