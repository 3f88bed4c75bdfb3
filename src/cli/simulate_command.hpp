#pragma once
// `softdrop simulate`: generate or load a medium and push one or many droplets through it.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/common_options.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::cli {

struct SimulateArgs {
  MediumArgs medium;
  std::string save_medium_file;  ///< save the medium used
  DropletParams droplet;
  RunOptions run;
  BatchOptions batch;
  double x0 = std::numeric_limits<double>::quiet_NaN();
  std::string format = "table";
  std::string runs_csv, paths_csv, trace_csv, snapshots_csv, json_file;
  bool quiet = false;        ///< no progress on stderr
  SecondDropletArgs second;  ///< a second droplet after each
  /// --from-sweep DB --sweep-droplet P:M:D [--sweep-id ID]: one droplet of a stored sweep again.
  std::string from_sweep, sweep_droplet;
  std::int64_t sweep_id = 0;  ///< 0: the only sweep of the file
};

/// Registers the subcommand and its options on `app`; returns it.
CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args);

/// Runs it; throws std::exception with a one-line message on bad input.
/// Checks the options (and that output paths can be written) without running; throws
/// std::invalid_argument naming the bad parameter.
void check_simulate(SimulateArgs& args);
/// With --from-sweep (else nothing): takes the medium, the droplet and exit options and the start of the named
/// droplet from the sweep's store (simulate_from_sweep.cpp), refusing any of those options given
/// on `command` (or in a config file) with one line naming it.
void take_sweep_droplet(SimulateArgs& args, const CLI::App& command);
int run_simulate(SimulateArgs& args);
/// run_simulate with a second droplet after each (--second-droplet), on the medium it made.
int run_simulate_two(SimulateArgs& args, const Medium& medium);

}  // namespace softdrop::cli
