#pragma once
// `softdrop validate`: the held-out tortuosity of a medium (a grain file, or the arrangement a
// search stored): droplets from many random starts, at the droplet's time step and at half of it.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "cli/common_options.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::cli {

struct ValidateArgs {
  std::string medium;  ///< a grain file, or
  std::string db;      ///< a search history, with run (and generation)
  std::int64_t run = 0;
  std::int64_t generation = -1;  ///< -1: the run's best
  HeldOutOptions held_out;
  bool same_dt_only = false;  ///< no second run at dt / 2
  DropletParams droplet;
  RunOptions run_options;
  std::string format = "table";
  std::string json_file, runs_csv;
  bool quiet = false;
};

/// Registers the subcommand and its options on `app`; returns it.
CLI::App* add_validate_command(CLI::App& app, ValidateArgs& args);
/// Checks the options without running; throws std::invalid_argument naming the bad one.
void check_validate(ValidateArgs& args, const CLI::App& command);
int run_validate(ValidateArgs& args, const CLI::App& command);

}  // namespace softdrop::cli
