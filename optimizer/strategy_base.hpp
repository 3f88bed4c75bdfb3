#pragma once
// What the strategies (strategy.cpp, cmaes_strategy.cpp) share: the current arrangement, the
// robust objectives' re-measure, keeping a candidate, and the candidates' random streams.
// Internal to softdrop_opt.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "evaluation.hpp"
#include "strategy.hpp"
#include "util/random.hpp"

namespace softdrop::detail {

// The random stream of candidate k of generation g: the same for every strategy.
inline std::uint64_t stream(const SearchOptions& o, std::int64_t g, int k) {
  return derive_seed(derive_seed(o.seed, static_cast<std::uint64_t>(g)), static_cast<std::uint64_t>(k));
}

// The candidate of the generation that passed with the highest T (the earliest on a tie), -1 if none.
inline int best_passed(const std::vector<const Candidate*>& candidates) {
  int best = -1;
  for (const Candidate* c : candidates)
    if (c && c->eval.outcome == Outcome::passed &&
        (best < 0 || c->eval.tortuosity > candidates[static_cast<std::size_t>(best)]->eval.tortuosity))
      best = c->index;
  return best;
}

class StrategyBase : public Strategy {
 public:
  StrategyBase(const SearchOptions& o, Configuration current) : o_(o), current_(std::move(current)) {}
  const SearchOptions& options() const override { return o_; }
  const Configuration& current() const override { return current_; }
  void remeasure(double value, const std::vector<double>& values) override {
    current_.eval.tortuosity = value;
    current_.eval.values = values;
  }
  void adopt(Configuration arrangement) override { current_ = std::move(arrangement); }
  using Strategy::propose;
  // The paper's candidates: its move kinds, steps and streams (the strategies that override this
  // have moves of their own).
  Candidate propose(std::int64_t generation, int k) const override {
    return make_candidate(current_, generation, k, o_);
  }

 protected:
  int keep(std::int64_t generation, const std::vector<const Candidate*>& candidates, int k) {
    if (k < 0) return -1;
    const Candidate& c = *candidates[static_cast<std::size_t>(k)];
    current_ = {generation, c.medium, c.eval};
    return k;
  }
  // The best strict improvement of the current arrangement, -1 if none.
  int best_improvement(const std::vector<const Candidate*>& candidates) const {
    return detail::best_improvement(candidates, current_.eval, o_.objective);
  }

  SearchOptions o_;
  Configuration current_;
};

// CMA-ES through pagmo2 (cmaes_strategy.cpp). `state` is "" (a new search) or the JSON array of
// the state() of every generation stored so far, in order, which it replays.
std::unique_ptr<Strategy> make_cmaes(const SearchOptions& options, Configuration current, const std::string& state);

}  // namespace softdrop::detail
