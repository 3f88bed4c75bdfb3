#include "softdrop/batch.hpp"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>

#include "softdrop/random.hpp"

namespace softdrop {

double batch_start_x(const BatchOptions& options, const Medium& medium, const DropletParams& params,
                     int i) {
  if (!std::isnan(options.start_x)) return options.start_x;
  Rng rng(derive_seed(options.seed, static_cast<std::uint64_t>(i)));
  if (medium.periodic) return rng.uniform(0, medium.width);
  return rng.uniform(params.radius, medium.width - params.radius);
}

std::vector<RunSummary> run_batch(const DropletParams& params, const Medium& medium,
                                  const RunOptions& run_options, const BatchOptions& options,
                                  const std::function<void(int, int)>& progress) {
  const int k = options.droplets;
  std::vector<RunSummary> results(static_cast<std::size_t>(k));
  std::mutex progress_mutex;
  int done = 0;
  // Each droplet is a sequential simulation of its own, so results do not depend on the schedule.
  auto body = [&](const tbb::blocked_range<int>& range) {
    Simulation sim(params, medium);
    for (int i = range.begin(); i != range.end(); ++i) {
      results[static_cast<std::size_t>(i)] =
          sim.run(batch_start_x(options, medium, params, i), run_options);
      if (progress) {
        std::lock_guard lock(progress_mutex);
        progress(++done, k);
      }
    }
  };
  if (options.threads > 0) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(options.threads));
    tbb::parallel_for(tbb::blocked_range<int>(0, k, 1), body);
  } else {
    tbb::parallel_for(tbb::blocked_range<int>(0, k, 1), body);
  }
  return results;
}

BatchStats summarize(const std::vector<RunSummary>& runs) {
  BatchStats b;
  b.droplets = static_cast<int>(runs.size());
  double sum = 0, steps = 0;
  for (const RunSummary& r : runs) {
    steps += static_cast<double>(r.steps);
    switch (r.outcome) {
      case Outcome::passed:
        ++b.passed;
        sum += r.tortuosity;
        break;
      case Outcome::stuck: ++b.stuck; break;
      case Outcome::timeout: ++b.timeout; break;
      case Outcome::diverged: ++b.diverged; break;
    }
  }
  if (b.passed > 0) b.mean_tortuosity = sum / b.passed;
  if (b.passed > 1) {
    double ss = 0;
    for (const RunSummary& r : runs)
      if (r.outcome == Outcome::passed)
        ss += (r.tortuosity - b.mean_tortuosity) * (r.tortuosity - b.mean_tortuosity);
    b.standard_error = std::sqrt(ss / (b.passed - 1) / b.passed);
  }
  if (b.droplets > 0) {
    b.stuck_fraction = static_cast<double>(b.stuck) / b.droplets;
    b.mean_steps = steps / b.droplets;
  }
  return b;
}

}  // namespace softdrop
