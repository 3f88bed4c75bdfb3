// Many pairs of droplets through one medium (run_two_droplet_batch, batch.hpp): worker threads
// take the pairs in index order, each stepping several together (run_pairs_interleaved).
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "sim/lane_policy.hpp"
#include "sim/pair_lanes.hpp"
#include "softdrop/batch.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {

std::vector<TwoDropletSummary> run_two_droplet_batch(const DropletParams& droplet, const Medium& medium,
                                                     const RunOptions& run, const BatchOptions& options,
                                                     const SecondDroplet& second,
                                                     const std::function<void(int, int)>& progress) {
  const int k = options.droplets;
  if (k < 0) throw std::invalid_argument("droplets = " + std::to_string(k) + ": must be >= 0");
  std::string why;
  if (!second.IsValid(droplet, &why)) throw std::invalid_argument(why);
  std::vector<TwoDropletSummary> results(static_cast<std::size_t>(k));
  std::atomic<int> next{0};
  std::mutex mutex;
  int done = 0;
  std::exception_ptr error;
  // A thread's lanes, each a droplet of a pair; a pair's summary does not depend on who steps it beside.
  const int lanes = std::max(2, batch_lanes(options.lanes));
  auto worker = [&] {
    try {
      run_pairs_interleaved(
          lanes, droplet, medium, run, second,
          [&](PairJob* job) {
            if (options.stop && options.stop->load(std::memory_order_relaxed)) return false;
            const int i = next.fetch_add(1);
            if (i >= k) return false;
            *job = PairJob{batch_start_x(options, medium, droplet, i), i};
            return true;
          },
          [&](std::int64_t i, TwoDropletSummary&& summary) {
            results[static_cast<std::size_t>(i)] = std::move(summary);
            if (progress) {
              std::lock_guard lock(mutex);
              progress(++done, k);
            }
          });
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      next.store(k);  // the others start no new pair
    }
  };
  std::vector<std::thread> pool;
  const int workers = std::min(k, detail::worker_threads(options.threads));
  for (int t = 1; t < workers; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  // Every pair below the counter ran to its end; none above it started.
  results.resize(static_cast<std::size_t>(std::min(k, next.load())));
  return results;
}

}  // namespace softdrop
