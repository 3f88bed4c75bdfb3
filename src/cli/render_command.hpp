#pragma once
// `softdrop render medium|snapshots|paths|search|animation|trace|curves`: pictures through the one drawing
// module (softdrop/render.hpp).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/common_options.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/render.hpp"

namespace softdrop::cli {

struct RenderArgs {
  std::string output;
  int size = 800;
  double dpi = 72;
  std::string background = "#ffffff", grain_colour = "#1f2938", touched_colour = "#40454d", path_colour = "#cc1a1a",
              droplet_colour = "#1f4fcc", stuck_colour = "#1f4fcc";
  bool no_caption = false;
  bool scale_bar = false;
  bool quiet = false;  ///< no progress on stderr
  MediumArgs medium;
  DropletParams droplet;
  RunOptions run;
  double x0 = std::numeric_limits<double>::quiet_NaN();  ///< default: the middle
  std::vector<double> times;                             ///< snapshots
  BatchOptions batch;                                    ///< paths
  double alpha = 0;                                      ///< paths: 0 = automatic
  int path_interval = 50;                                ///< paths: steps between recorded centre-of-mass points
  std::string db;                                        ///< search
  std::int64_t run_id = 0;
  std::int64_t generation = -1;
  std::string curve;              ///< search: best-T chart
  double fps = 25, speed = 0.02;  ///< animation: frames per second, time units per second
  int max_frames = 1500;
  std::string csv;                       ///< trace: the area samples
  std::vector<std::string> dbs, labels;  ///< curves: the searches and their legend labels
  std::string x_axis = "evaluations";    ///< curves: evaluations or seconds
  SecondDropletArgs second;              ///< animation: a second droplet after the first
};

/// The medium the options name, generated or loaded.
Medium medium_of(RenderArgs& args);
/// Whether any two grains overlap (such grains are drawn as their solid union).
bool grains_overlap(const Medium& medium);
/// A polyline of the points (x, y).
Polyline path_line(const std::vector<double>& x, const std::vector<double>& y, Rgba colour, double width);
/// The droplet's start: --x0, checked against the box, or the middle.
double start_of(const RenderArgs& args, const Medium& medium);
/// The picture options as a RenderStyle; throws std::invalid_argument naming a bad colour or size.
RenderStyle style_of(const RenderArgs& args);
/// `render curves` (render_curves.cpp).
int render_curves(RenderArgs& args);
/// `render animation` (render_animation.cpp).
int render_animation_command(RenderArgs& args);

/// Registers `render` and its seven subcommands; returns `render`.
CLI::App* add_render_command(CLI::App& app, RenderArgs& args);
/// Runs the chosen subcommand of `render`.
/// Checks the options shared by the pictures, and those of the picture `which` names (render
/// paths' droplets and path memory), without drawing; throws std::invalid_argument.
void check_render(RenderArgs& args, const std::string& which);
int run_render(RenderArgs& args, const CLI::App& render);

}  // namespace softdrop::cli
