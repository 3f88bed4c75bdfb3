#pragma once
// `softdrop tortuosity`: one medium's tortuosities side by side: the droplet's (held-out starts),
// and its pore space's on a pixel image, geometric, diffusive and hydrodynamic (with the
// permeability), each at a resolution and at its double, with the value extrapolated from the two.

#include <CLI/CLI.hpp>
#include <string>

#include "cli/common_options.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::cli {

struct TortuosityArgs {
  MediumArgs medium;
  int pixels = 500;           ///< across the box's width, at the coarser resolution (the finer has twice)
  bool pixels_given = false;  ///< --pixels was given (otherwise an image medium is taken at its own)
  HeldOutOptions droplets;    ///< the droplet's T: starts and seed (0 starts: no droplet)
  DropletParams droplet;
  RunOptions run;
  std::string format = "table";
  std::string json_file, csv_file;
  bool flow = true;          ///< solve the creeping flow (hydrodynamic T, permeability)
  std::string picture;       ///< the pore space drawn: the concentration and shortest paths
  std::string flow_picture;  ///< the flow drawn: the speed and shortest paths
  int size = 600;            ///< its width in points
  bool quiet = false;
};

/// Registers the subcommand and its options on `app`; returns it.
CLI::App* add_tortuosity_command(CLI::App& app, TortuosityArgs& args);
/// Checks the options without running; throws std::invalid_argument naming the bad one.
void check_tortuosity(TortuosityArgs& args);
int run_tortuosity(TortuosityArgs& args);
/// The coarser resolution, pixels across: --pixels, or an image medium's own columns when it was
/// not given.
int tortuosity_pixels(const TortuosityArgs& a, const Medium& medium);
/// Throws std::invalid_argument naming --pixels when the smallest grain's radius would span fewer
/// than 4 pixels (the solves' first-order error is then tens of percent); returns how many it spans.
double check_resolution(const Medium& medium, int pixels);

}  // namespace softdrop::cli
