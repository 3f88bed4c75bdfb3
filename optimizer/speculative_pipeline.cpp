// The speculative pipeline (speculative_pipeline.hpp): the drive's generations, with the
// candidates of later generations evaluated speculatively (and acceptances predicted) so that
// every thread and lane stays busy, with the history of one generation at a time.
#include "speculative_pipeline.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "drive_test_seam.hpp"
#include "evaluation.hpp"
#include "sim/interleaved.hpp"
#include "softdrop/search.hpp"
#include "strategy.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {
using detail::as_evaluation;
using detail::best_improvement;
using detail::evaluation_run;

// Speculative evaluation (Strategy::speculative): worker threads take candidates (g, k) in order,
// up to `depth` generations ahead of the last completed one, each made from the strategy state the
// pipeline expects generation g to have. A lineage is a state and the generations handed out from
// it, from the one where it begins on, each made from the state its predecessors leave if none of
// their candidates improves on anything (the paper's hill climb: the same parent; es: smaller
// steps). A newer lineage ends the older ones where it begins (`dead_from`), wholly those that
// begin at a later generation (a prediction for an earlier generation, below): their candidates of
// those generations are dropped, or cancelled while they run.
//
// A lineage begins as a prediction. Once a finished candidate of a generation improves on the
// arrangement the generation was made from, the state after it is not the one its lineage assumed.
// The pipeline goes on from Strategy::foresee, which takes the candidates still running to improve
// on nothing. This holds for any generation handed out whole, not only the next one to complete: a
// later generation's state is the one its earlier, undecided generations predict, so its own
// prediction is conditional on theirs. A candidate finishing later may improve too (for the
// paper's hill climb, by more; for es, by anything, as a success changes the steps): the
// prediction changes and the work made from the first is dropped. A prediction made for an earlier
// generation ends those of the later ones with their lineage. The last candidate of a generation
// to arrive settles its prediction, so a generation always completes as predicted or, without a
// prediction, as its lineage assumed. Every candidate that reaches a generation was made from that
// generation's true state, so the history is that of one generation at a time.
class SpeculativePipeline::Impl {
 public:
  Impl(Search& search, int workers, int lanes, std::int64_t last_allowed)
      : search_(search), upto_(last_allowed), lanes_(lanes) {
    const int lambda = search.options().lambda;
    // Far enough ahead that a slow (stuck) candidate does not leave the lanes empty: four times the
    // generations in flight (bench/README.md, "Lanes of a search").
    depth_ = std::max<std::int64_t>(2, 4 * workers * lanes / lambda);
    completed_ = search.last_generation();
    add_lineage(search.strategy().clone(), completed_ + 1);
    next_gen_ = completed_ + 1;
    for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { work(); });
  }
  ~Impl() {
    {
      std::lock_guard lock(m_);
      stopping_.store(true, std::memory_order_relaxed);  // also cancels the runs still in flight
    }
    cv_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Generation next() {
    const auto t0 = std::chrono::steady_clock::now();
    const int lambda = search_.options().lambda;
    std::vector<Candidate> candidates;
    // All under the lock, from taking the candidates out of done_ to completed_: predict(), which
    // workers call as their candidates finish, must never see this generation without them (it
    // would take it to accept nothing and predict the next one from the wrong parent; with the
    // completion outside the lock, a 20 ms pause here made four search tests throw, and
    // Search.ASlowCompletionKeepsTheHistory pauses here).
    std::unique_lock lock(m_);
    const std::int64_t g = completed_ + 1;
    cv_.wait(lock, [&] {
      if (error_) return true;
      for (int k = 0; k < lambda; ++k)
        if (!done_.count({g, k})) return false;
      return true;
    });
    if (error_) std::rethrow_exception(error_);
    for (int k = 0; k < lambda; ++k) {
      auto it = done_.find({g, k});
      stats_.kept_steps += it->second.eval.steps;
      candidates.push_back(std::move(it->second));
      done_.erase(it);
    }
#if defined(SOFTDROP_TEST_HOOKS)
    if (before_completion_) before_completion_();
#endif
    const Generation gen = search_.complete(
        std::move(candidates), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    completed_ = gen.number;
    // predict() saw the last of these candidates arrive, so it foresaw what complete() did: the
    // prediction if it made one, else no improvement. Either way the next generation's lineage
    // begins from that.
    const auto p = predicted_.find(gen.number);
    const int expected = p != predicted_.end() ? p->second.k : -1;
    const std::string expected_state = before(gen.number + 1)->state();
    if (gen.accepted != expected || gen.state != expected_state)
      throw std::logic_error("search pipeline: generation " + std::to_string(gen.number) + " kept " +
                             std::to_string(gen.accepted) + " with state '" + gen.state + "', foreseen " +
                             std::to_string(expected) + " with '" + expected_state + "'");
    if (p != predicted_.end()) predicted_.erase(p);
    for (const std::shared_ptr<Lineage>& l : lines_)  // what no generation to come is made from
      l->before.erase(l->before.begin(), l->before.lower_bound(completed_));
    predict();  // the next generation's candidates may all have finished already
    lock.unlock();
    cv_.notify_all();
    return gen;
  }

  SpeculationStats stats() {
    std::lock_guard lock(m_);
    return stats_;
  }

 private:
  struct Lineage {
    std::int64_t start = 0;  // the first generation it makes
    // By generation (from start on, the ones still needed): the state its candidates are made from.
    std::map<std::int64_t, std::shared_ptr<const Strategy>> before;
    std::atomic<std::int64_t> dead_from{std::numeric_limits<std::int64_t>::max()};
  };
  struct Prediction {
    int k = -1;                             // the candidate expected to be kept
    std::shared_ptr<const Strategy> after;  // the state after the generation
  };

  // Under m_. The state generation g (>= line.start, at most one past the last it made) is made
  // from.
  const std::shared_ptr<const Strategy>& before(Lineage& line, std::int64_t g) {
    auto it = line.before.find(g);
    if (it != line.before.end()) return it->second;
    if (line.before.empty() || g < line.before.begin()->first)
      throw std::logic_error("search pipeline: generation " + std::to_string(g) + " is not in its lineage");
    int kept = -1;
    const std::vector<const Candidate*> none(static_cast<std::size_t>(search_.options().lambda), nullptr);
    std::shared_ptr<const Strategy> s = before(line, g - 1)->foresee(g - 1, none, &kept);
    return line.before.emplace(g, std::move(s)).first->second;
  }
  // Under m_. The state generation g is made from, in the lineage that makes it now: the newest one
  // begun at or before g.
  const std::shared_ptr<const Strategy>& before(std::int64_t g) {
    for (auto it = lines_.rbegin(); it != lines_.rend(); ++it)
      if ((*it)->start <= g) return before(**it, g);
    throw std::logic_error("search pipeline: no lineage makes generation " + std::to_string(g));
  }

  // Under m_. Generations from `start` on are made from `strategy` as their predecessors leave it;
  // every generation before `start` has been handed out whole. The predictions from `start` on
  // were made from the lineages ended here.
  void begin_lineage(std::shared_ptr<const Strategy> strategy, std::int64_t start) {
    // A prediction for an earlier generation ends the lineages begun after it as well.
    for (const std::shared_ptr<Lineage>& l : lines_)
      if (l->dead_from.load(std::memory_order_relaxed) > start) l->dead_from.store(start, std::memory_order_relaxed);
    // Drop those with nothing left to end: wholly ended, or ended where the generations completed.
    std::erase_if(lines_, [this](const std::shared_ptr<Lineage>& l) {
      const std::int64_t dead_from = l->dead_from.load(std::memory_order_relaxed);
      return dead_from <= l->start || dead_from <= completed_ + 1;
    });
    add_lineage(std::move(strategy), start);
    for (auto it = done_.lower_bound({start, 0}); it != done_.end(); it = done_.erase(it)) {
      ++stats_.dropped;
      stats_.dropped_steps += it->second.eval.steps;
    }
    for (auto it = predicted_.lower_bound(start); it != predicted_.end(); it = predicted_.erase(it))
      ++stats_.mispredictions;
    next_gen_ = start;
    next_k_ = 0;
  }

  // Under m_. The newest lineage, from which work is handed out: lines_.back().
  void add_lineage(std::shared_ptr<const Strategy> strategy, std::int64_t start) {
    auto line = std::make_shared<Lineage>();
    line->start = start;
    line->before.emplace(start, std::move(strategy));
    lines_.push_back(std::move(line));
  }

  // Under m_. Goes through the generations handed out whole, from the next to complete on, and
  // predicts the state after the first whose finished candidates improve on the arrangement it
  // was made from and which has no prediction, or a different one, yet.
  void predict() {
    const auto lambda = static_cast<std::size_t>(search_.options().lambda);
    for (std::int64_t g = completed_ + 1; g < next_gen_ && g <= upto_; ++g) {
      const std::shared_ptr<const Strategy>& from = before(g);
      std::vector<const Candidate*> finished(lambda, nullptr);
      for (std::size_t k = 0; k < lambda; ++k) {
        const auto it = done_.find({g, static_cast<int>(k)});
        if (it != done_.end()) finished[k] = &it->second;
      }
      // No prediction while no finished candidate improves: g is taken to improve on nothing, as its
      // lineage does.
      if (best_improvement(finished, from->current().eval.tortuosity) < 0) continue;
      int kept = -1;
      std::shared_ptr<const Strategy> after = from->foresee(g, finished, &kept);
      auto p = predicted_.find(g);
      if (p != predicted_.end() && p->second.k == kept && p->second.after->state() == after->state()) continue;
      if (p != predicted_.end()) {
        ++stats_.mispredictions;
        predicted_.erase(p);
      }
      ++stats_.predictions;
      if (g > completed_ + 1) ++stats_.predictions_ahead;
      predicted_.emplace(g, Prediction{kept, after});
      begin_lineage(std::move(after), g + 1);  // nothing after g + 1 is left to look at
      return;
    }
  }

  // A worker steps up to `lanes_` candidates together (run_interleaved); each evaluation gets the
  // bits it gets alone.
  void work() {
    const SearchOptions& options = search_.options();
    struct Job {
      std::int64_t g = 0;
      int k = 0;
      std::shared_ptr<Lineage> line;
      Candidate c;
      std::unique_ptr<Simulation> sim;
      RunOptions run;
      std::int64_t polls = 0;  // of run.cancelled, one every run.check_interval steps
      std::chrono::steady_clock::time_point t0;
    };
    std::map<std::int64_t, Job> jobs;  // by id; nodes stay put, so sims may point into them
    std::int64_t next_id = 0;
    auto fail = [&](std::exception_ptr e) {
      std::lock_guard lock(m_);
      if (!error_) error_ = std::move(e);
      cv_.notify_all();
    };
    auto next = [&](DropletJob* job, bool may_wait) {
      std::unique_lock lock(m_);
      auto ready = [&] {
        return stopping_.load(std::memory_order_relaxed) || (next_gen_ <= upto_ && next_gen_ <= completed_ + depth_);
      };
      if (may_wait) cv_.wait(lock, ready);
      if (stopping_.load(std::memory_order_relaxed) || !ready()) return false;
      Job j;
      j.g = next_gen_;
      j.k = next_k_;
      if (++next_k_ == options.lambda) next_k_ = 0, ++next_gen_;
      j.line = lines_.back();
      const std::shared_ptr<const Strategy> from = before(*j.line, j.g);  // work() reports a throw
      lock.unlock();
      const std::int64_t id = next_id++;
      try {
        j.c = from->propose(j.g, j.k);
        j.t0 = std::chrono::steady_clock::now();
        j.run = evaluation_run(options.run);
        Job& placed = jobs.emplace(id, std::move(j)).first->second;
        // Work made useless by a new lineage stops early instead of running on.
        placed.run.cancelled = [this, &placed] {
          ++placed.polls;
          return stopping_.load(std::memory_order_relaxed) ||
                 placed.g >= placed.line->dead_from.load(std::memory_order_relaxed);
        };
        placed.sim = std::make_unique<Simulation>(options.droplet, placed.c.medium);
        *job = {placed.sim.get(), 0.5 * placed.c.medium.width, &placed.run, id};
        return true;
      } catch (...) {
        jobs.erase(id);  // if it got that far
        fail(std::current_exception());
        return false;
      }
    };
    auto done = [&](std::int64_t id, RunSummary&& summary) {
      auto it = jobs.find(id);
      Job& j = it->second;
      j.c.eval = as_evaluation(std::move(summary), j.t0);
      {
        std::lock_guard lock(m_);
        if (j.g < j.line->dead_from.load(std::memory_order_relaxed)) {
          done_.emplace(std::pair{j.g, j.k}, std::move(j.c));
          predict();
        } else {
          ++stats_.dropped;
          stats_.dropped_steps += j.c.eval.steps;
        }
      }
      cv_.notify_all();
      jobs.erase(it);
    };
    auto cancelled = [&](std::int64_t id) {
      const auto it = jobs.find(id);
      if (!stopping_.load(std::memory_order_relaxed)) {
        std::lock_guard lock(m_);
        ++stats_.dropped;
        stats_.dropped_steps += it->second.polls * it->second.run.check_interval;  // it stopped at a poll
      }
      jobs.erase(it);
    };
    try {
      run_interleaved(lanes_, next, done, cancelled);
    } catch (...) {
      fail(std::current_exception());
    }
  }

  Search& search_;
  const std::int64_t upto_;
  const int lanes_;
#if defined(SOFTDROP_TEST_HOOKS)
  const std::function<void()> before_completion_ = test_seam::before_completion();
#endif
  std::int64_t depth_ = 1;
  std::mutex m_;
  std::condition_variable cv_;
  // The lineages with generations not yet ended, oldest first; the last one is the newest, whose
  // generations from its start on are handed out.
  std::vector<std::shared_ptr<Lineage>> lines_;
  std::int64_t completed_ = 0, next_gen_ = 0;
  int next_k_ = 0;
  std::map<std::int64_t, Prediction> predicted_;  // standing predictions, by generation
  std::map<std::pair<std::int64_t, int>, Candidate> done_;
  std::exception_ptr error_;
  std::atomic<bool> stopping_{false};  // set under m_ (for the waits), read anywhere
  SpeculationStats stats_;
  std::vector<std::thread> threads_;
};

#if defined(SOFTDROP_TEST_HOOKS)
std::function<void()>& test_seam::before_completion() {
  static std::function<void()> hook;
  return hook;
}
#endif

SpeculativePipeline::SpeculativePipeline(Search& search, int workers, int lanes, std::int64_t last_allowed)
    : impl_(std::make_unique<Impl>(search, workers, lanes, last_allowed)) {}
SpeculativePipeline::~SpeculativePipeline() = default;
Generation SpeculativePipeline::next() { return impl_->next(); }
SpeculationStats SpeculativePipeline::stats() { return impl_->stats(); }

}  // namespace softdrop
