#pragma once
// Option groups shared by the commands that build media and push droplets (simulate, optimize),
// so each option has one name, one help text and one default everywhere.

#include <CLI/CLI.hpp>
#include <string>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::cli {

/// A medium to generate, or a grain file to load instead.
struct MediumArgs {
  MediumOptions options;
  std::string kind = "overlapping";
  std::string radii = "uniform";
  bool walls = false;
  std::string file;  ///< load instead of generating
};

/// Registers --medium, --kind, --porosity, --width, ... in a "Medium" group. With
/// `fixed_count`, the medium is non-overlapping with --grains grains (the search's media) and
/// --kind/--porosity are not offered.
CLI::Option_group* add_medium_options(CLI::App* app, MediumArgs& a, bool fixed_count);
/// Registers the droplet's physical parameters (--masses, --nrt, ...) in a "Droplet" group.
CLI::Option_group* add_droplet_options(CLI::App* app, DropletParams& d);
/// Registers --max-steps, --stuck-window, --stuck-distance in `group`.
void add_exit_options(CLI::Option_group* group, RunOptions& r);

/// Parses the names into options.kind / radii / periodic and validates them (unless a file is
/// given); throws std::invalid_argument naming the bad parameter.
void resolve_medium(MediumArgs& a);

}  // namespace softdrop::cli
