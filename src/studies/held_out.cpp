#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "softdrop/batch.hpp"
#include "util/quantile.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

HeldOutRuns describe(double dt, std::vector<RunSummary> runs) {
  HeldOutRuns r;
  r.dt = dt;
  const BatchStats s = summarize(runs);
  r.starts = s.droplets, r.passed = s.passed, r.stuck = s.stuck, r.timeout = s.timeout, r.diverged = s.diverged;
  r.pass_fraction = s.droplets > 0 ? static_cast<double>(s.passed) / s.droplets : 0.0;
  r.mean_t = s.passed > 0 ? s.mean_tortuosity : kNaN;
  r.standard_error = s.passed > 1 ? s.standard_error : kNaN;
  std::vector<double> t;
  for (const RunSummary& run : runs)
    if (run.outcome == Outcome::passed) t.push_back(run.tortuosity);
  std::sort(t.begin(), t.end());
  r.q1 = t.empty() ? kNaN : detail::linear_quantile(t, 0.25);
  r.median = t.empty() ? kNaN : detail::linear_quantile(t, 0.5);
  r.q3 = t.empty() ? kNaN : detail::linear_quantile(t, 0.75);
  r.runs = std::move(runs);
  return r;
}

}  // namespace

bool HeldOutOptions::IsValid(std::string* why) const {
  if (starts < 1 || starts > kMaxHeldOutStarts)
    return detail::fail(why, "starts = " + std::to_string(starts) + ": must be in [1, 1e6]");
  if (!detail::valid_threads(threads, why)) return false;
  return true;
}

HeldOutValue held_out_value(const DropletParams& droplet, const Medium& medium, const RunOptions& run,
                            const HeldOutOptions& options, const std::function<void(int, int)>& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  BatchOptions batch;
  batch.droplets = options.starts;
  batch.seed = options.seed;
  batch.threads = options.threads;
  const int total = options.starts * (options.half_dt ? 2 : 1);
  HeldOutValue v;
  v.at_dt = describe(droplet.dt, run_batch(droplet, medium, run, batch, [&](int done, int) {
                       if (progress) progress(done, total);
                     }));
  if (!options.half_dt) return v;
  // Half the step over the same stretch of time: the step budget doubles; every other option is
  // in time units or counts checks, and stays.
  DropletParams half = droplet;
  half.dt = 0.5 * droplet.dt;
  RunOptions half_run = run;
  half_run.max_steps = run.max_steps > std::numeric_limits<std::int64_t>::max() / 2 ? run.max_steps : 2 * run.max_steps;
  v.at_half_dt = describe(half.dt, run_batch(half, medium, half_run, batch, [&](int done, int) {
                            if (progress) progress(options.starts + done, total);
                          }));
  std::vector<double> shifts;
  for (int i = 0; i < options.starts; ++i) {
    const RunSummary &a = v.at_dt.runs[static_cast<std::size_t>(i)],
                     &b = v.at_half_dt.runs[static_cast<std::size_t>(i)];
    if (a.outcome == Outcome::passed && b.outcome == Outcome::passed) shifts.push_back(b.tortuosity - a.tortuosity);
  }
  v.paired = static_cast<int>(shifts.size());
  double sum = 0;
  for (double d : shifts) sum += d;
  v.dt_shift = v.paired > 0 ? sum / v.paired : kNaN;
  double ss = 0;
  for (double d : shifts) ss += (d - v.dt_shift) * (d - v.dt_shift);
  v.dt_shift_error = v.paired > 1 ? std::sqrt(ss / (v.paired - 1) / v.paired) : kNaN;
  return v;
}

}  // namespace softdrop
