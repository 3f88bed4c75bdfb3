// Evaluating one generation's candidates together: every (candidate, start) droplet is a job, on
// up to `threads` threads, each stepping up to `lanes` droplets at once (run_interleaved), the
// lane exchange spreading the last ones over the threads. Each candidate's evaluation has the
// bits of evaluate() on its own: a droplet's run depends only on its medium and start.
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "evaluation.hpp"
#include "sim/interleaved.hpp"
#include "sim/lane_policy.hpp"
#include "sim/simulation_prototype.hpp"
#include "util/worker_threads.hpp"

namespace softdrop::detail {

void evaluate_candidates(std::vector<Candidate>& candidates, const SearchOptions& options, std::int64_t generation,
                         int threads, int lanes) {
  const int n = static_cast<int>(candidates.size());
  if (n == 0) return;
  // Common random numbers: every candidate's droplets start where the others' do.
  const std::vector<double> starts =
      objective_starts(options.objective, options.seed, generation, candidates.front().medium, options.droplet);
  const int per = static_cast<int>(starts.size());
  const int jobs = n * per;
  const int workers = std::min(jobs, worker_threads(threads));
  if (lanes <= 0) lanes = std::max(1, std::min(interleaved_lanes(), (jobs + workers - 1) / workers));
  const RunOptions run = evaluation_run(options.run);
  std::vector<std::unique_ptr<Simulation>> sims(static_cast<std::size_t>(jobs));
  // Each candidate's droplets share one model of its medium.
  std::vector<SimulationPrototype> prototypes(static_cast<std::size_t>(n));
  std::vector<RunSummary> runs(static_cast<std::size_t>(jobs));
  std::vector<int> left(static_cast<std::size_t>(n), per);  // droplets of each candidate not yet done
  std::vector<std::chrono::steady_clock::time_point> started(static_cast<std::size_t>(n));
  std::atomic<int> next{0};
  LaneExchange exchange;
  std::mutex m;
  std::exception_ptr error;
  auto worker = [&] {
    try {
      auto take = [&](DropletJob* job, bool) {
        if (next.load(std::memory_order_relaxed) >= jobs) return false;
        const int i = next.fetch_add(1);
        if (i >= jobs) return false;
        const auto u = static_cast<std::size_t>(i);
        const auto c = static_cast<std::size_t>(i / per);
        sims[u] = prototypes[c].copy(options.droplet, candidates[c].medium);
        if (i % per == 0) started[c] = std::chrono::steady_clock::now();
        job->sim = sims[u].get();
        job->x0 = starts[static_cast<std::size_t>(i % per)];
        job->options = &run;
        job->id = i;
        return true;
      };
      auto done = [&](std::int64_t id, RunSummary&& summary) {
        const auto u = static_cast<std::size_t>(id);
        const auto c = static_cast<std::size_t>(id / per);
        runs[u] = std::move(summary);
        sims[u].reset();
        bool last = false;
        {
          std::lock_guard lock(m);
          last = --left[c] == 0;
        }
        if (!last) return;
        std::vector<RunSummary> mine(std::make_move_iterator(runs.begin() + static_cast<std::ptrdiff_t>(c) * per),
                                     std::make_move_iterator(runs.begin() + static_cast<std::ptrdiff_t>(c + 1) * per));
        candidates[c].eval = as_evaluation(options.objective, std::move(mine), started[c]);
      };
      run_interleaved(lanes, take, done, nullptr, &exchange);
    } catch (...) {
      std::lock_guard lock(m);
      if (!error) error = std::current_exception();
      next.store(jobs);  // the others start no new droplet
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace softdrop::detail
