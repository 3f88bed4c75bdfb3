// The drive: generations until a stop condition (DriveOptions), one at a time through
// Search::next, or through the speculative pipeline where the strategy allows it.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/lane_policy.hpp"
#include "softdrop/search.hpp"
#include "speculative_pipeline.hpp"
#include "strategy.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {
using detail::num;

bool DriveOptions::IsValid(std::string* why) const {
  if (lanes < 0 || lanes > 64) return detail::fail(why, "lanes = " + std::to_string(lanes) + ": must be in [0, 64]");
  return true;
}

SearchSummary drive(Search& search, const DriveOptions& options, const GenerationCallback& callback) {
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  SearchSummary s;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const int workers = detail::worker_threads(options.threads);
  const SearchOptions& so = search.options();
  const int lanes =
      options.lanes > 0 ? options.lanes : speculative_lanes(so.lambda, workers, so.droplet.constraint_order);
  std::unique_ptr<SpeculativePipeline> pipeline;
  // Speculation assumes the paper's rule (a generation that keeps nothing changes nothing); other
  // strategies evaluate one generation at a time, its candidates on every thread and lane.
  // A robust objective has K droplets a candidate to fill the threads, and re-runs the parent on
  // every generation's starts, which a generation ahead cannot know.
  if (options.speculate && search.strategy().speculative() && !so.objective.robust() && (workers > 1 || lanes > 1) &&
      search.last_generation() < options.generations)
    pipeline = std::make_unique<SpeculativePipeline>(search, workers, lanes, options.generations);
  for (;;) {
    if (search.last_generation() >= options.generations) {
      s.termination = Termination::generations;
      s.message = "reached generation " + std::to_string(options.generations);
      break;
    }
    if (options.stop && options.stop->load()) {
      s.termination = Termination::interrupted;
      s.message = "interrupted after generation " + std::to_string(search.last_generation());
      break;
    }
    if (options.time_limit > 0 && elapsed() >= options.time_limit) {
      s.termination = Termination::time_limit;
      s.message = "time limit of " + num(options.time_limit) + " s reached after generation " +
                  std::to_string(search.last_generation());
      break;
    }
    const Generation g = pipeline ? pipeline->next() : search.next(options.threads, options.lanes);
    ++s.generations_run;
    s.evaluations += static_cast<std::int64_t>(g.candidates.size());
    for (const Candidate& c : g.candidates) s.droplets += c.eval.droplets;
    s.droplets += g.parent.droplets;
    if (g.accepted >= 0) ++s.accepted;
    if (callback && !callback(g, search.best())) {
      s.termination = Termination::callback;
      s.message = "stopped by a callback after generation " + std::to_string(g.number);
      break;
    }
  }
  if (pipeline) {
    s.speculation = pipeline->stats();
    s.speculation.threads = workers;
    s.speculation.lanes = lanes;
  }
  s.last_generation = search.last_generation();
  s.best_t = search.best().eval.tortuosity;
  s.seconds = elapsed();
  return s;
}

}  // namespace softdrop
