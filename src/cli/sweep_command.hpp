#pragma once
// `softdrop sweep`: the tortuosity-porosity sweep into a resumable SQLite store, shardable, run by
// the library's run_sweep (softdrop/service.hpp) with the program's progress line, Ctrl-C and MPI
// ranks (sweep_command.cpp).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cli/common_options.hpp"
#include "cli/host.hpp"
#include "softdrop/service.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop::cli {

struct SweepArgs {
  std::string db = "sweep.db";
  SweepOptions sweep;
  MediumArgs medium;
  SecondDropletArgs second;               ///< parsed into sweep.second
  std::string preset;                     ///< quick or paper: defaults for options not given
  std::string media_stream = "held-out";  ///< parsed into sweep.stream
  std::string shard = "0/1";
  int threads = 0;
  bool quiet = false;
  std::string format = "table";
};

void add_sweep_command(CLI::App& app, SweepArgs& args);
/// Applies --preset and checks the options without running; returns the shard (i, n). Throws
/// std::invalid_argument naming the bad parameter.
std::pair<int, int> check_sweep(SweepArgs& args, const CLI::App& command);
/// Runs a sweep; with a host (see Host) nothing is printed on stdout and the signals are left to it.
int run_sweep(SweepArgs& args, const CLI::App& command, Host* host = nullptr);
/// The program's run of a sweep (`runner`: the MPI ranks'; empty: this process's threads):
/// run_sweep (service.hpp) with the program's lines on stderr (none when `quiet`) and its points
/// table on stdout in `format`, or with a host, the host's events and the summary handed to it.
/// Returns the exit code (130 or 143 after a signal the program handled, else 0).
int run_sweep_run(const SweepRun& run, bool quiet, const std::string& format, Host* host,
                  const SweepUnitsRunner& runner = {});
/// The shard of --shard "i/n"; throws std::invalid_argument naming it unless 0 <= i < n.
std::pair<int, int> parse_shard(const std::string& text);

}  // namespace softdrop::cli
