#pragma once
// The tortuosity-porosity sweep on the command line: `sweep` (into a resumable SQLite store,
// shardable; sweep_command.cpp), `sweep-merge` (sweep_merge_command.cpp) and `sweep-report`.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cli/common_options.hpp"
#include "cli/host.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {
class SweepStore;
}

namespace softdrop::cli {

struct SweepArgs {
  std::string db = "sweep.db";
  SweepOptions sweep;
  MediumArgs medium;
  std::string preset;                     ///< quick or paper: defaults for options not given
  std::string media_stream = "held-out";  ///< parsed into sweep.stream
  std::string shard = "0/1";
  int threads = 0;
  bool quiet = false;
  std::string format = "table";
};

struct SweepMergeArgs {
  std::string into;
  std::vector<std::string> inputs;
};

struct SweepReportArgs {
  std::string db = "sweep.db";
  std::int64_t sweep = 0;  ///< 0: the only one
  bool media = false;      ///< per-medium rows instead of per-porosity points
  std::string format = "table";
};

void add_sweep_commands(CLI::App& app, SweepArgs& sweep, SweepMergeArgs& merge, SweepReportArgs& report);
/// Applies --preset and checks the options without running; returns the shard (i, n). Throws
/// std::invalid_argument naming the bad parameter.
std::pair<int, int> check_sweep(SweepArgs& args, const CLI::App& command);
/// Runs a sweep; with a host (see Host) nothing is printed on stdout and the signals are left to it.
int run_sweep(SweepArgs& args, const CLI::App& command, Host* host = nullptr);
int run_sweep_merge(const SweepMergeArgs& args);
int run_sweep_report(const SweepReportArgs& args);
/// The sweep `id` of the store, or its only sweep when id is 0; throws std::invalid_argument
/// naming the file when it holds none or several. A sweep that holds fewer media than it has is
/// warned of on stderr: its readers' figures are of part of it.
std::int64_t pick_sweep(SweepStore& store, std::int64_t id, const std::string& db);

}  // namespace softdrop::cli
