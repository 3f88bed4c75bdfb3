// Evaluating one generation's candidates together: on up to `threads` threads, each stepping up to
// `lanes` candidates at once (run_interleaved), the lane exchange spreading the last ones over
// the threads. Each candidate's evaluation has the bits of evaluate() on its own.
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "evaluation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop::detail {

void evaluate_candidates(std::vector<Candidate>& candidates, const SearchOptions& options, int threads, int lanes) {
  const int k = static_cast<int>(candidates.size());
  if (k == 0) return;
  const int workers = std::min(k, worker_threads(threads));
  if (lanes <= 0) lanes = std::max(1, std::min(interleaved_lanes(), (k + workers - 1) / workers));
  const RunOptions run = evaluation_run(options.run);
  std::vector<std::unique_ptr<Simulation>> sims(static_cast<std::size_t>(k));
  std::vector<std::chrono::steady_clock::time_point> started(static_cast<std::size_t>(k));
  std::atomic<int> next{0};
  LaneExchange exchange;
  std::mutex m;
  std::exception_ptr error;
  auto worker = [&] {
    try {
      auto take = [&](DropletJob* job, bool) {
        if (next.load(std::memory_order_relaxed) >= k) return false;
        const int i = next.fetch_add(1);
        if (i >= k) return false;
        const auto u = static_cast<std::size_t>(i);
        sims[u] = std::make_unique<Simulation>(options.droplet, candidates[u].medium);
        started[u] = std::chrono::steady_clock::now();
        job->sim = sims[u].get();
        job->x0 = 0.5 * candidates[u].medium.width;  // as evaluate(): the middle of the top
        job->options = &run;
        job->id = i;
        return true;
      };
      auto done = [&](std::int64_t id, RunSummary&& summary) {
        const auto u = static_cast<std::size_t>(id);
        candidates[u].eval = as_evaluation(std::move(summary), started[u]);
        sims[u].reset();
      };
      run_interleaved(lanes, take, done, nullptr, &exchange);
    } catch (...) {
      std::lock_guard lock(m);
      if (!error) error = std::current_exception();
      next.store(k);  // the others start no new candidate
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace softdrop::detail
