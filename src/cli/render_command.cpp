#include "cli/render_command.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "cli/history_command.hpp"
#include "cli/output.hpp"
#include "cli/simulate_output.hpp"
#include "sim/lane_policy.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"
#include "softdrop/store.hpp"
#include "studies/area_trace.hpp"
#include "util/worker_threads.hpp"

namespace softdrop::cli {

Medium medium_of(RenderArgs& a) {
  resolve_medium(a.medium);
  return a.medium.file.empty() ? generate_medium(a.medium.options) : load_medium_file(a.medium);
}

// Whether any two grains overlap (sorted by their left edge, each compared with those that start
// before it ends; periodic images are not needed for the answer in any medium of many grains).
bool grains_overlap(const Medium& m) {
  std::vector<Grain> g = m.grains;
  std::sort(g.begin(), g.end(), [](const Grain& a, const Grain& b) { return a.x - a.r < b.x - b.r; });
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size() && g[j].x - g[j].r < g[i].x + g[i].r; ++j)
      if (std::hypot(g[i].x - g[j].x, g[i].y - g[j].y) < g[i].r + g[j].r) return true;
  return false;
}

Polyline path_line(const std::vector<double>& x, const std::vector<double>& y, Rgba colour, double width) {
  Polyline p;
  p.x = x;
  p.y = y;
  p.colour = colour;
  p.width = width;
  return p;
}

// The droplet's start: --x0, checked against the box, or the middle.
double start_of(const RenderArgs& a, const Medium& medium) {
  check_start_x(a.x0, medium, a.droplet);
  return std::isnan(a.x0) ? 0.5 * medium.width : a.x0;
}

RenderStyle style_of(const RenderArgs& a) {
  RenderStyle s;
  s.width = a.size;
  s.dpi = a.dpi;
  s.background = parse_colour(a.background);
  s.grain = parse_colour(a.grain_colour);
  s.touched = parse_colour(a.touched_colour);
  s.caption = !a.no_caption;
  s.scale_bar = a.scale_bar;
  std::string why;
  if (!s.IsValid(&why)) throw std::invalid_argument(why);
  return s;
}

// Overlapping grains are drawn as their solid union; others as outlined discs.
void draw_picture(const Scene& scene, RenderStyle style, const std::string& path) {
  style.solid_grains = grains_overlap(scene.medium);
  render_scene(scene, style, path);
}

std::string medium_caption(const Medium& m) { return medium_words(m, exact_porosity(m), 4); }

// The part of a path inside or below the medium (y <= top): the start above it is cut at y = top.
Polyline below_top(Polyline p, double top) {
  std::size_t first = 0;
  while (first < p.y.size() && p.y[first] > top) ++first;
  if (first == p.y.size()) return Polyline{{}, {}, p.colour, p.width};
  if (first > 0) {  // the crossing of y = top, between the last point above and the first below
    const std::size_t i = first - 1;
    const double f = (p.y[i] - top) / (p.y[i] - p.y[first]);
    p.x[i] += f * (p.x[first] - p.x[i]);
    p.y[i] = top;
    first = i;
  }
  p.x.erase(p.x.begin(), p.x.begin() + static_cast<std::ptrdiff_t>(first));
  p.y.erase(p.y.begin(), p.y.begin() + static_cast<std::ptrdiff_t>(first));
  return p;
}

namespace {

void check_droplet(const RenderArgs& a) {
  std::string why;
  if (!a.droplet.IsValid(&why)) throw std::invalid_argument(why);
  if (!a.run.IsValid(&why)) throw std::invalid_argument(why);
  if (!std::isnan(a.x0) && !std::isfinite(a.x0)) throw std::invalid_argument("x0 = " + fmt(a.x0) + ": must be finite");
}

int render_medium(RenderArgs& a) {
  Scene scene;
  scene.medium = medium_of(a);
  scene.caption = medium_caption(scene.medium);
  scene.top_room = 0;
  draw_picture(scene, style_of(a), a.output);
  return 0;
}

int render_snapshots(RenderArgs& a) {
  if (a.times.empty()) throw std::invalid_argument("times: at least one snapshot time is needed");
  const RenderStyle style = style_of(a);
  Scene scene;
  scene.medium = medium_of(a);
  Simulation sim(a.droplet, scene.medium);
  RunOptions run = a.run;
  check_snapshot_times(a.times, run, a.droplet, "times");
  run.snapshot_times = a.times;
  run.path_interval = 20;
  check_recording(run, 1, a.droplet.masses);
  const double x0 = start_of(a, scene.medium);
  const RunSummary r = sim.run(x0, run);
  const Rgba droplet = parse_colour(a.droplet_colour);
  scene.lines.push_back(path_line(r.path_x, r.path_y, parse_colour(a.path_colour), 1.2));
  for (const Snapshot& sn : r.snapshots) {
    Polyline ring = path_line(sn.x, sn.y, droplet, 1.8);
    ring.closed = true;
    ring.fill = Rgba{droplet.r, droplet.g, droplet.b, 0.15};
    // Draw the ring where its centre is: shift it by a whole number of widths.
    double cx = 0;
    for (double x : sn.x) cx += x;
    cx /= static_cast<double>(sn.x.size());
    if (scene.medium.periodic) {
      const double shift = std::floor(cx / scene.medium.width) * scene.medium.width;
      for (double& x : ring.x) x -= shift;
    }
    // Its time, just right of the ring.
    const double right = *std::max_element(ring.x.begin(), ring.x.end());
    double cy = 0;
    for (double y : ring.y) cy += y;
    scene.labels.push_back({right + 0.3 * a.droplet.radius, cy / static_cast<double>(ring.y.size()),
                            "t = " + fmt(sn.time, 4), Rgba{droplet.r, droplet.g, droplet.b, 1}});
    scene.lines.push_back(std::move(ring));
  }
  scene.caption = std::to_string(r.snapshots.size()) + " snapshots; " + to_string(r.outcome) +
                  (r.outcome == Outcome::passed ? ", T = " + fmt(r.tortuosity, 5) : "") + "; " +
                  medium_caption(scene.medium);
  if (r.snapshots.size() < a.times.size())
    std::cerr << "render: " << a.times.size() - r.snapshots.size() << " snapshot time(s) after the run ended ("
              << to_string(r.outcome) << " at t = " << fmt(static_cast<double>(r.steps) * a.droplet.dt, 4) << ")\n";
  draw_picture(scene, style, a.output);
  return 0;
}

// The ring's area every few steps (trace_area), entry and exit marked; S0 is the area at the entry.
constexpr int kTraceInterval = 20;  // steps between area samples of the trace

int render_trace(RenderArgs& a) {
  RunOptions recorded = a.run;
  recorded.area_interval = kTraceInterval;
  check_recording(recorded, 1, a.droplet.masses);
  const RenderStyle style = style_of(a);
  if (!a.csv.empty()) check_output_path("--csv", a.csv);
  const Medium medium = medium_of(a);
  const double x0 = start_of(a, medium);
  const AreaTrace trace = trace_area(a.droplet, medium, x0, a.run, kTraceInterval);
  const RunSummary& whole = trace.run;
  const std::vector<double>& t = trace.t;
  const std::vector<double>& area = trace.area;
  const double enter = trace.enter, leave = trace.leave, s0 = trace.s0;
  if (std::isnan(s0)) throw std::runtime_error("trace: the droplet never reached the medium");
  Series ratio;
  ratio.colour = parse_colour(a.droplet_colour);
  for (std::size_t i = 0; i < t.size(); ++i) ratio.x.push_back(t[i]), ratio.y.push_back(area[i] / s0);
  Chart c;
  c.series = {ratio};
  c.hlines = {1.0};
  c.markers = {enter};
  c.marker_labels = {"enters"};
  if (!std::isnan(leave)) c.markers.push_back(leave), c.marker_labels.push_back("leaves");
  c.x_label = "time t (time units)";
  c.y_label = "area ratio S(t) / S₀";
  c.title = std::string(to_string(whole.outcome)) +
            (whole.outcome == Outcome::passed ? ", T = " + fmt(whole.tortuosity, 5) : "") + "; " +
            medium_caption(medium);
  if (!a.csv.empty()) write_area_traces(a.csv, {trace});
  render_chart(c, style, a.output);
  const double lo = trace.min_ratio, hi = trace.max_ratio;
  std::cerr << "trace: enters at t = " << fmt(enter, 5)
            << ", leaves at t = " << (std::isnan(leave) ? "never" : fmt(leave, 5)) << "; inside the medium S/S0 spans ["
            << fmt(lo, 5) << ", " << fmt(hi, 5) << "]\n";
  return 0;
}

}  // namespace

// Run before every picture (run_render), so the commands below need not check the droplet again.
void check_render(RenderArgs& a, const std::string& which) {
  check_picture_path("--output", a.output);
  style_of(a);
  check_droplet(a);
  resolve_medium(a.medium);
  if (which == "paths") paths_run(a.run, a.batch.droplets, a, a.droplet);
}

int run_render(RenderArgs& a, const CLI::App& render) {
  const std::string which = render.get_subcommands().front()->get_name();
  check_render(a, which);
  if (which == "medium") return render_medium(a);
  if (which == "snapshots") return render_snapshots(a);
  if (which == "paths") return render_paths(a);
  if (which == "search") return render_search(a);
  if (which == "trace") return render_trace(a);
  if (which == "curves") return render_curves(a);
  return render_animation_command(a);
}

}  // namespace softdrop::cli
