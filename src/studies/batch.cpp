#include "softdrop/batch.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "sim/interleaved.hpp"
#include "sim/lane_policy.hpp"
#include "sim/simulation_prototype.hpp"
#include "util/random.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {

double batch_start_x(const BatchOptions& options, const Medium& medium, const DropletParams& params, int i) {
  if (!std::isnan(options.start_x)) return options.start_x;
  Rng rng(derive_seed(options.seed, static_cast<std::uint64_t>(i)));
  if (medium.periodic) return rng.uniform(0, medium.width);
  return rng.uniform(params.radius, medium.width - params.radius);
}

std::vector<RunSummary> run_batch(const DropletParams& params, const Medium& medium, const RunOptions& run_options,
                                  const BatchOptions& options, const std::function<void(int, int)>& progress) {
  const int k = options.droplets;
  if (k < 0) throw std::invalid_argument("droplets = " + std::to_string(k) + ": must be >= 0");
  if (options.lanes < 0 || options.lanes > 64)
    throw std::invalid_argument("lanes = " + std::to_string(options.lanes) + ": must be in [1, 64], or 0 (chosen)");
  const int lanes = batch_lanes(options.lanes);
  std::vector<RunSummary> results(static_cast<std::size_t>(k));
  std::mutex progress_mutex;
  int done = 0;
  std::atomic<int> next_droplet{0};
  // Droplet i's simulation while it runs. Any thread may finish a droplet (the lane exchange hands
  // the last ones to idle threads), so they are kept by droplet, not by thread.
  std::vector<std::unique_ptr<Simulation>> running(static_cast<std::size_t>(k));
  SimulationPrototype prototype;  // every droplet's simulation shares one model
  LaneExchange exchange;
  // Each thread takes droplets from one counter and steps `lanes` of them together; each droplet is
  // a sequential simulation of its own, so results do not depend on the schedule.
  auto worker = [&] {
    std::vector<std::unique_ptr<Simulation>> pool;  // simulations not running a droplet
    auto next = [&](DropletJob* job, bool) {
      // Asked again after every step while a lane is idle: look before taking, so the counter
      // stays near k however long the last droplets run.
      if (next_droplet.load(std::memory_order_relaxed) >= k) return false;
      if (options.stop && options.stop->load(std::memory_order_relaxed)) return false;
      const int i = next_droplet.fetch_add(1);
      if (i >= k) return false;
      std::unique_ptr<Simulation>& sim = running[static_cast<std::size_t>(i)];
      if (pool.empty()) {
        sim = prototype.copy(params, medium);
      } else {
        sim = std::move(pool.back());
        pool.pop_back();
      }
      job->sim = sim.get();
      job->x0 = batch_start_x(options, medium, params, i);
      job->options = &run_options;
      job->id = i;
      return true;
    };
    auto finished = [&](std::int64_t id, RunSummary&& summary) {
      if (options.on_finished) {
        std::lock_guard lock(progress_mutex);
        options.on_finished(static_cast<int>(id), summary);
      }
      results[static_cast<std::size_t>(id)] = std::move(summary);
      pool.push_back(std::move(running[static_cast<std::size_t>(id)]));
      if (progress) {
        std::lock_guard lock(progress_mutex);
        progress(++done, k);
      }
    };
    run_interleaved(lanes, next, finished, nullptr, &exchange);
  };
  // Long-lived workers that may block at the lane exchange: plain threads, the calling thread one
  // of them, no more than there are droplets.
  const int workers = std::min(k, detail::worker_threads(options.threads));
  std::exception_ptr error;
  auto fail = [&](std::exception_ptr e) {
    std::lock_guard lock(progress_mutex);
    if (!error) error = std::move(e);
    next_droplet.store(k);  // the others start no new droplet
  };
  auto guarded = [&] {
    try {
      worker();
    } catch (...) {
      fail(std::current_exception());
    }
  };
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < workers; ++t) pool.emplace_back(guarded);
  } catch (...) {  // a thread could not start: stop handing out droplets, finish the running ones, report
    fail(std::current_exception());
  }
  guarded();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  // Every droplet below the counter was started and has run to its end; none above it started.
  results.resize(static_cast<std::size_t>(std::min(k, next_droplet.load())));
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
      case Outcome::stuck:
        ++b.stuck;
        break;
      case Outcome::timeout:
        ++b.timeout;
        break;
      case Outcome::diverged:
        ++b.diverged;
        break;
    }
  }
  if (b.passed > 0) b.mean_tortuosity = sum / b.passed;
  if (b.passed > 1) {
    double ss = 0;
    for (const RunSummary& r : runs)
      if (r.outcome == Outcome::passed) ss += (r.tortuosity - b.mean_tortuosity) * (r.tortuosity - b.mean_tortuosity);
    b.standard_error = std::sqrt(ss / (b.passed - 1) / b.passed);
  }
  if (b.droplets > 0) {
    b.stuck_fraction = static_cast<double>(b.stuck) / b.droplets;
    b.mean_steps = steps / b.droplets;
  }
  return b;
}

}  // namespace softdrop
