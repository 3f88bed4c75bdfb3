// `softdrop render animation`: a droplet (or, with --second-droplet, two, one after the other)
// pushed through the medium, drawn frame by frame from the run's own recorded rings.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/output.hpp"
#include "cli/render_command.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::cli {
namespace {

// One droplet of the animation: its run (rings recorded at the frames' times, and its path), when
// that run began on the animation's clock (0, or the second droplet's release), and its colours.
struct Track {
  const RunSummary* run = nullptr;
  double begins = 0;
  Rgba ring, path;
};

// Draws a track at time t of the animation's clock into the scene, the medium moved by (dx, dy):
// the last ring recorded by then (the first, at rest above the medium, before the run began), and
// the path so far.
void draw_track(const Track& k, double t, double dx, double dy, const Medium& medium, Scene& scene) {
  const RunSummary& run = *k.run;
  const double own = t - k.begins;
  std::size_t s = 0;
  while (s + 1 < run.snapshots.size() && run.snapshots[s + 1].time <= own) ++s;
  const Snapshot& sn = run.snapshots[s];
  std::size_t points = 0;
  while (points < run.path_t.size() && run.path_t[points] <= own) ++points;
  std::vector<double> px(run.path_x.begin(), run.path_x.begin() + static_cast<std::ptrdiff_t>(points));
  std::vector<double> py(run.path_y.begin(), run.path_y.begin() + static_cast<std::ptrdiff_t>(points));
  for (double& v : px) v += dx;
  for (double& v : py) v += dy;
  scene.lines.push_back(path_line(px, py, k.path, 1.5));
  Polyline ring = path_line(sn.x, sn.y, k.ring, 2);
  ring.closed = true;
  ring.fill = Rgba{k.ring.r, k.ring.g, k.ring.b, 0.25};
  double cx = 0;
  for (double& v : ring.x) v += dx, cx += v / static_cast<double>(ring.x.size());
  for (double& v : ring.y) v += dy;
  if (medium.periodic) {
    const double shift = std::floor(cx / medium.width) * medium.width;
    for (double& x : ring.x) x -= shift;
  }
  scene.lines.push_back(std::move(ring));
}

std::string outcome_words(const RunSummary& r) {
  return std::string(to_string(r.outcome)) + (r.outcome == Outcome::passed ? ", T = " + fmt(r.tortuosity, 5) : "");
}

}  // namespace

int render_animation_command(RenderArgs& a) {
  if (!std::isfinite(a.speed) || a.speed <= 0) throw std::invalid_argument("speed = " + fmt(a.speed) + ": must be > 0");
  if (!std::isfinite(a.fps) || a.fps <= 0 || a.fps > 100)
    throw std::invalid_argument("fps = " + fmt(a.fps) + ": must be in (0, 100]");
  check_second_droplet(a.second, a.droplet);
  RenderStyle style = style_of(a);
  const Medium medium = medium_of(a);
  style.solid_grains = grains_overlap(medium);
  const double x0 = start_of(a, medium);
  check_second_start(a.second, x0, medium, a.droplet);
  const double dt = a.droplet.dt;
  // First the whole run (deterministic), to know its length; then the same run again, recording
  // the rings at each frame's step and the paths, from which the frames are drawn (the run's own
  // steps, shaking included). The second droplet's clock starts at its release.
  const bool two = a.second.on();
  std::int64_t end = 0;
  double released_at = 0;
  if (two) {
    const TwoDropletSummary whole = run_two_droplets(a.droplet, medium, x0, a.run, a.second.second);
    released_at = whole.released ? whole.released_at : 0;
    end = std::max<std::int64_t>(whole.first.steps,
                                 whole.released ? std::llround(whole.released_at / dt) + whole.second.steps : 0);
  } else {
    end = Simulation(a.droplet, medium).run(x0, a.run).steps;
  }
  const double steps_per_frame = a.speed / (a.fps * dt);
  const int frames = static_cast<int>(std::ceil(static_cast<double>(end) / steps_per_frame)) + 1;
  if (frames > a.max_frames)
    throw std::invalid_argument("max-frames = " + std::to_string(a.max_frames) + ": the run needs " +
                                std::to_string(frames) + " frames at --speed " + fmt(a.speed) + " and --fps " +
                                fmt(a.fps));
  std::vector<double> times;  // on the animation's clock
  RunOptions recorded = a.run;
  recorded.path_interval = 10;
  recorded.snapshot_times.clear();
  for (int f = 0; f < frames; ++f) {
    times.push_back(static_cast<double>(std::min<std::int64_t>(end, std::llround(f * steps_per_frame))) * dt);
    recorded.snapshot_times.push_back(times.back());
    // The second droplet records on its own clock.
    if (two && times.back() > released_at) recorded.snapshot_times.push_back(times.back() - released_at);
  }
  std::vector<Track> tracks;
  RunSummary run;
  TwoDropletSummary pair;
  Simulation sim(a.droplet, medium);
  if (two) {
    pair = run_two_droplets(a.droplet, medium, x0, recorded, a.second.second);
    tracks.push_back({&pair.first, 0, parse_colour(a.droplet_colour), parse_colour(a.path_colour)});
    // The second in orange, its path with it.
    if (pair.released)
      tracks.push_back({&pair.second, pair.released_at, Rgba{0.85, 0.45, 0.05, 1}, Rgba{0.85, 0.45, 0.05, 1}});
  } else {
    run = sim.run(x0, recorded);
    tracks.push_back({&run, 0, parse_colour(a.droplet_colour), parse_colour(a.path_colour)});
  }
  const double top_room = sim.start_height() - medium.height + 1.6 * a.droplet.radius;
  // When the medium began to shake, on the first droplet's clock (a pair's droplets share it; the
  // second's run began at its release); NaN if it never did.
  const double shaken_at =
      two ? std::fmin(pair.first.shaken_at, pair.released_at + pair.second.shaken_at) : run.shaken_at;
  Progress progress("render: frames");
  render_animation(
      frames, a.fps,
      [&](int f, Scene& scene) {
        const double t = times[static_cast<std::size_t>(f)];
        // A shaken medium is drawn as it moves, A (1 - cos 2 pi f t) from where it was, and the
        // droplet and its path with it (the run's coordinates are the medium's).
        double dx = 0, dy = 0;
        if (a.droplet.vibrates() && t >= shaken_at) a.droplet.vibration_displacement(t - shaken_at, &dx, &dy);
        scene.medium = medium;
        for (Grain& g : scene.medium.grains) g.x += dx, g.y += dy;
        scene.image_shift_x = dx, scene.image_shift_y = dy;  // an image medium's pixels
        scene.top_room = top_room;
        for (const Track& k : tracks) draw_track(k, t, dx, dy, medium, scene);
        if (two)
          scene.caption =
              "t = " + fmt(t, 3) + " (first: " + outcome_words(pair.first) +
              (pair.released ? "; second, from t = " + fmt(pair.released_at, 3) + ": " + outcome_words(pair.second)
                             : "; second never released") +
              ")";
        else
          scene.caption = "t = " + fmt(t, 3) + " (" + outcome_words(run) +
                          (t >= shaken_at ? "; shaken since t = " + fmt(shaken_at, 3) : "") + ")";
        if (!a.quiet) progress.update(f + 1, frames);
      },
      style, a.output);
  return 0;
}

}  // namespace softdrop::cli
