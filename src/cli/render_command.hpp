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
  int search_droplets = -1;       ///< search: held-out paths drawn (-1: 50 for a robust objective, 0 for single)
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
/// Draws a scene; overlapping grains as their solid union, others as outlined discs.
void draw_picture(const Scene& scene, RenderStyle style, const std::string& path);
/// The medium in a caption's words: grains, porosity, box.
std::string medium_caption(const Medium& medium);
/// The part of a path inside or below the medium (y <= top): the start above it is cut at y = top.
Polyline below_top(Polyline path, double top);

/// The run options that record paths for a picture of `droplets` droplets (render_paths.cpp),
/// after checking the count and the memory of the paths in flight; throws std::invalid_argument.
RunOptions paths_run(const RunOptions& run, int droplets, const RenderArgs& args, const DropletParams& droplet);
/// The batch's droplets with their paths as drawn (a few points a pixel of a picture `size_points`
/// wide at `dpi`), progress on stderr unless quiet. Throws std::runtime_error if the paths drawn
/// would hold more than 1e8 points.
std::vector<RunSummary> run_paths(const DropletParams& droplet, const Medium& medium, const RunOptions& run,
                                  BatchOptions batch, const RenderArgs& args);
/// Adds each run's path below the medium's top: passed ones in --path-colour, the others in
/// --stuck-colour, each at `alpha` (0: 10 / runs, at least 0.03).
void add_paths(Scene& scene, const std::vector<RunSummary>& runs, const RenderArgs& args, double alpha);

/// Fills each grain by the share of `runs` that touched it (Scene::filled).
void shade_by_touches(Scene& scene, const std::vector<RunSummary>& runs);

/// `render paths` and `render search` (render_paths.cpp, render_search.cpp).
int render_paths(RenderArgs& args);
int render_search(RenderArgs& args);
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
