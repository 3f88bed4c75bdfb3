#include "calibration.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "area_trace.hpp"
#include "softdrop/batch.hpp"
#include "util/random.hpp"
#include "util/validation.hpp"

namespace softdrop {

double paper_tortuosity(double phi) { return 1.58 - 0.58 * std::pow(phi, 3.87); }

SweepOptions CalibrationOptions::default_sweep() {
  SweepOptions s;
  s.porosities = {0.5, 0.6, 0.7, 0.8, 0.9, 0.95};
  s.media = 10;
  s.droplets = 20;
  s.stream = MediaStream::calibration;
  return s;
}

bool CalibrationOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!sweep.IsValid(why)) return false;
  if (!(trace_porosity > 0 && trace_porosity < 1))
    return fail("trace-porosity = " + detail::num(trace_porosity) + ": must be in (0, 1)");
  if (trace_media < 0 || trace_media > 1000)
    return fail("trace-media = " + std::to_string(trace_media) + ": must be in [0, 1000]");
  if (trace_droplets < 0 || trace_droplets > 10000)
    return fail("trace-droplets = " + std::to_string(trace_droplets) + ": must be in [0, 10000]");
  if (!(rest_scale > 0 && rest_scale <= 1e6))
    return fail("rest-scale = " + detail::num(rest_scale) + ": must be in (0, 1e6]");
  return true;
}

namespace {

// Fills the per-porosity points and the sweep's figures of `r` from the sweep's own points (in
// the order of sweep.porosities); returns the sweep's diverged droplets.
long score_points(const SweepOptions& sweep, const std::vector<SweepMedium>& media, CalibrationResult* r) {
  const std::size_t count = sweep.porosities.size();
  const std::vector<SweepPoint> measured = sweep_points(media);
  r->points.assign(count, {});
  for (const SweepMedium& m : media)
    for (const SweepDroplet& d : m.droplets) r->steps += static_cast<double>(d.steps);
  double sum2 = 0, measured2 = 0;
  long droplets = 0, stuck = 0, diverged = 0;
  for (std::size_t i = 0; i < count; ++i) {
    CalibrationPoint& p = r->points[i];
    p.target_porosity = p.porosity = sweep.porosities[i];
    for (const SweepPoint& q : measured) {
      if (q.target_porosity != p.target_porosity) continue;
      p.porosity = q.porosity, p.droplets = q.droplets, p.passed = q.passed, p.stuck = q.stuck;
      p.diverged = q.diverged, p.mean_t = q.mean_t, p.standard_error = q.standard_error;
      p.media_passed = q.media_passed, p.media_standard_error = q.media_standard_error;
    }
    p.paper_t = paper_tortuosity(p.porosity);
    const double miss = p.passed >= 2 ? p.mean_t - p.paper_t : p.paper_t - 1;
    p.within = p.passed >= 2 && std::abs(miss) <= std::max(0.03, 2 * p.media_standard_error);
    sum2 += miss * miss;
    if (p.passed >= 2) measured2 += miss * miss, ++r->measured;
    r->within += p.within;
    droplets += p.droplets, stuck += p.stuck, diverged += p.diverged;
  }
  r->rms_distance = count > 0 ? std::sqrt(sum2 / static_cast<double>(count)) : 0;
  r->measured_rms = r->measured > 0 ? std::sqrt(measured2 / r->measured) : 0;
  r->stuck_fraction = droplets > 0 ? static_cast<double>(stuck) / static_cast<double>(droplets) : 0;
  return diverged;
}

// The traces' media: the sweep's box and radii, non-overlapping at trace_porosity.
Medium trace_medium(const CalibrationOptions& o, int index) {
  MediumOptions mo = o.sweep.medium;
  mo.kind = MediumKind::non_overlapping;
  mo.porosity = o.trace_porosity;
  mo.grains = 0;
  mo.seed = derive_seed(o.sweep.seed, 0x5452414345ULL + static_cast<std::uint64_t>(index));  // "TRACE"
  return generate_medium(mo);
}

}  // namespace

double resting_limit(double scale) { return 0.01 * std::sqrt(scale); }

double resting_travel(const DropletParams& droplet, double scale) {
  const double time = std::sqrt(scale);  // (scale 1 leaves every number as it was)
  Medium floor{200 * scale, 200 * scale, true, {}, nullptr};
  for (int i = 0; i < 10; ++i) floor.grains.push_back({(10.0 + 20.0 * i) * scale, 100 * scale, 12 * scale});
  Simulation sim(droplet, floor);
  sim.place_above(37.0 * scale);
  const auto settle = static_cast<std::int64_t>(std::llround(0.4 * time / droplet.dt));
  const auto follow = static_cast<std::int64_t>(std::llround(1.0 * time / droplet.dt));
  for (std::int64_t k = 0; k < settle; ++k)
    if (!sim.step()) return NAN;
  double px, py, path = 0;
  sim.centre_of_mass(&px, &py);
  for (std::int64_t k = 0; k < follow; ++k) {
    if (!sim.step()) return NAN;
    double cx, cy;
    sim.centre_of_mass(&cx, &cy);
    path += std::hypot(cx - px, cy - py);
    px = cx, py = cy;
  }
  return path / (static_cast<double>(follow) * droplet.dt);
}

CalibrationResult run_calibration(const CalibrationOptions& o, const DropletParams& droplet, int threads,
                                  const std::function<void(long, long)>& progress) {
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(why);
  if (!droplet.IsValid(&why)) throw std::invalid_argument(why);
  SweepOptions sweep = o.sweep;
  sweep.droplet = droplet;
  sweep.stream = MediaStream::calibration;  // tuning sees only these media; sweeps default to others
  const std::vector<SweepUnit> units = sweep_units(sweep);
  const long traces = static_cast<long>(o.trace_media) * o.trace_droplets;
  const long total = static_cast<long>(units.size()) * sweep.droplets + traces;
  std::atomic<long> done{0};
  std::mutex report;
  auto tick = [&](long n) {
    const long now = done += n;
    if (!progress) return;
    std::lock_guard<std::mutex> lock(report);
    progress(now, total);
  };

  std::vector<SweepMedium> media;
  run_sweep_units(sweep, units, threads, [&](SweepMedium&& m) {
    tick(static_cast<long>(m.droplets.size()));
    media.push_back(std::move(m));
  });
  // Completion order varies with the threads; the sums must not.
  std::sort(media.begin(), media.end(), [](const SweepMedium& a, const SweepMedium& b) {
    return std::pair(a.unit.porosity, a.unit.medium) < std::pair(b.unit.porosity, b.unit.medium);
  });
  CalibrationResult r;
  const long sweep_diverged = score_points(sweep, media, &r);

  std::vector<Medium> trace_media;
  for (int m = 0; m < o.trace_media; ++m) trace_media.push_back(trace_medium(o, m));
  std::vector<AreaTrace> runs(static_cast<std::size_t>(traces));
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(0L, traces, [&](long k) {
      const int m = static_cast<int>(k / o.trace_droplets), d = static_cast<int>(k % o.trace_droplets);
      BatchOptions starts;
      starts.seed = derive_seed(o.sweep.seed ^ 0x5354415254ULL, static_cast<std::uint64_t>(m));
      const Medium& medium = trace_media[static_cast<std::size_t>(m)];
      const double x0 = batch_start_x(starts, medium, droplet, d);
      runs[static_cast<std::size_t>(k)] = trace_area(droplet, medium, x0, o.sweep.run, 1000);
      tick(1);
    });
  });
  double lo = INFINITY, hi = -INFINITY;
  for (const AreaTrace& t : runs) {
    ++r.trace_runs;
    r.trace_passed += t.run.outcome == Outcome::passed;
    r.trace_diverged += t.run.outcome == Outcome::diverged;
    if (std::isnan(t.s0)) continue;
    lo = std::min(lo, t.min_ratio), hi = std::max(hi, t.max_ratio);
  }
  r.area_min = std::isfinite(lo) ? lo : NAN;
  r.area_max = std::isfinite(hi) ? hi : NAN;
  r.area_both_sides = std::isfinite(lo) && lo < 0.95 && hi > 1.02;
  r.diverged_fraction =
      total > 0 ? static_cast<double>(sweep_diverged + r.trace_diverged) / static_cast<double>(total) : 0;
  r.resting_travel = resting_travel(droplet, o.rest_scale);
  r.comes_to_rest = r.resting_travel <= resting_limit(o.rest_scale);  // NaN (diverged) does not
  r.score = r.rms_distance + r.diverged_fraction + (r.comes_to_rest ? 0 : 1) + 0.05 * (r.area_both_sides ? 0 : 1) +
            0.05 * r.stuck_fraction;
  return r;
}

}  // namespace softdrop
