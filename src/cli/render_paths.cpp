// `softdrop render paths`: many droplets' centre-of-mass paths over one medium, and the recording
// and drawing of such paths that `render search` shares.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "cli/output.hpp"
#include "cli/render_command.hpp"
#include "cli/simulate_output.hpp"
#include "sim/lane_policy.hpp"
#include "util/worker_threads.hpp"

namespace softdrop::cli {
namespace {

// A finished droplet's path as drawn: the points at least `spacing` (half a pixel, in length
// units) from the last one kept, and the last; its times and other records dropped. A path in a
// picture needs no more, and a long batch keeps no more.
void thin_path(RunSummary& r, double spacing) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < r.path_x.size(); ++i) {
    const bool last = i + 1 == r.path_x.size();
    if (kept > 0 && !last && std::hypot(r.path_x[i] - r.path_x[kept - 1], r.path_y[i] - r.path_y[kept - 1]) < spacing)
      continue;
    r.path_x[kept] = r.path_x[i], r.path_y[kept] = r.path_y[i];
    ++kept;
  }
  r.path_x.resize(kept), r.path_y.resize(kept);
  r.path_x.shrink_to_fit(), r.path_y.shrink_to_fit();
  r.path_t = {}, r.area_t = {}, r.area = {}, r.snapshots = {};
}

}  // namespace

// The limits of a picture of paths, which --check applies too: the droplet count, the colours'
// alpha and the memory of the paths being recorded: the droplets in flight at once (each thread's
// lanes) may each run --max-steps; a finished path keeps only what the picture shows (thin_path).
RunOptions paths_run(const RunOptions& run, int droplets, const RenderArgs& a, const DropletParams& droplet) {
  if (droplets < 1 || droplets > 1'000'000)
    throw std::invalid_argument("droplets = " + std::to_string(droplets) + ": must be in [1, 1e6]");
  if (!(a.alpha >= 0 && a.alpha <= 1)) throw std::invalid_argument("alpha = " + fmt(a.alpha) + ": must be in [0, 1]");
  if (a.path_interval < 1)
    throw std::invalid_argument("path-interval = " + std::to_string(a.path_interval) + ": must be >= 1");
  RunOptions recorded = run;
  recorded.path_interval = a.path_interval;
  const long threads = detail::worker_threads(a.batch.threads);
  check_recording(recorded, std::min<long>(droplets, threads * batch_lanes(a.batch.lanes)), droplet.masses);
  return recorded;
}

std::vector<RunSummary> run_paths(const DropletParams& droplet, const Medium& medium, const RunOptions& run,
                                  BatchOptions batch, const RenderArgs& a) {
  Progress progress("render: droplets done");
  const double spacing = 0.5 * medium.width / (a.size * a.dpi / 72.0);
  std::atomic<bool> over{false};
  double points = 0;
  batch.stop = &over;
  batch.on_finished = [&](int, RunSummary& r) {
    thin_path(r, spacing);
    points += static_cast<double>(r.path_x.size());
    if (points > kMaxRecordedSamples) over = true;
  };
  std::vector<RunSummary> runs = run_batch(droplet, medium, run, batch, [&](int done, int total) {
    if (!a.quiet) progress.update(done, total);
  });
  if (over)
    throw std::runtime_error("render: the paths of the first " + std::to_string(runs.size()) +
                             " droplets hold more than 1e8 points as drawn; draw fewer --droplets");
  return runs;
}

void add_paths(Scene& scene, const std::vector<RunSummary>& runs, const RenderArgs& a, double alpha) {
  if (!(alpha > 0))
    alpha = std::min(1.0, std::max(0.03, 10.0 / static_cast<double>(std::max<std::size_t>(runs.size(), 1))));
  Rgba passed = parse_colour(a.path_colour), stuck = parse_colour(a.stuck_colour);
  passed.a = stuck.a = alpha;
  for (const RunSummary& r : runs)
    scene.lines.push_back(below_top(path_line(r.path_x, r.path_y, r.outcome == Outcome::passed ? passed : stuck, 1.5),
                                    scene.medium.height));
}

void shade_by_touches(Scene& scene, const std::vector<RunSummary>& runs) {
  std::vector<int> touched_by(scene.medium.grains.size(), 0);
  for (const RunSummary& r : runs)
    for (std::int32_t i : r.touched)
      if (i >= 0 && static_cast<std::size_t>(i) < touched_by.size()) ++touched_by[static_cast<std::size_t>(i)];
  scene.filled.assign(touched_by.size(), 0);
  if (runs.empty()) return;
  for (std::size_t i = 0; i < touched_by.size(); ++i)
    scene.filled[i] = static_cast<double>(touched_by[i]) / static_cast<double>(runs.size());
}

int render_paths(RenderArgs& a) {
  const RunOptions run = paths_run(a.run, a.batch.droplets, a, a.droplet);
  const RenderStyle style = style_of(a);
  Scene scene;
  scene.medium = medium_of(a);
  const std::vector<RunSummary> runs = run_paths(a.droplet, scene.medium, run, a.batch, a);
  add_paths(scene, runs, a, a.alpha);
  // Separate grains are shaded by how many droplets met them; overlapping ones are drawn as their
  // union, where discs shaded one by one would darken each overlap.
  const bool shaded = scene.medium.image == nullptr && !grains_overlap(scene.medium);
  if (shaded) shade_by_touches(scene, runs);
  const BatchStats stats = summarize(runs);
  scene.caption = std::to_string(stats.droplets) + " droplets: " + std::to_string(stats.passed) + " passed, " +
                  std::to_string(stats.droplets - stats.passed) + " did not" +
                  (stats.passed ? ", <T> = " + fmt(stats.mean_tortuosity, 4) : "") +
                  (shaded ? ", each grain shaded by the share of them that touched it" : "") + "; " +
                  medium_caption(scene.medium);
  draw_picture(scene, style, a.output);
  return 0;
}

}  // namespace softdrop::cli
