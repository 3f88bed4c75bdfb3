// The search strategies (strategy.hpp): the paper's hill climb, a (1 + lambda) evolution strategy
// with adaptive step sizes, late acceptance hill climbing and simulated annealing.
#include "strategy.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "evaluation.hpp"
#include "strategy_base.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {
using detail::best_passed;
using detail::improves;
using detail::StrategyBase;
using detail::stream;

// The paper's hill climb: every candidate from the current arrangement, which is also the best.
class Paper final : public StrategyBase {
 public:
  using StrategyBase::StrategyBase;
  std::string state() const override { return ""; }
  bool speculative() const override { return true; }
  std::unique_ptr<Strategy> clone() const override { return std::make_unique<Paper>(*this); }

 protected:
  int decide(std::int64_t generation, const std::vector<const Candidate*>& candidates) override {
    return keep(generation, candidates, best_improvement(candidates));
  }
};

// (1 + lambda) evolution strategy: the paper's two move kinds, spread over the candidates in the
// paper's proportion (every single-every-th candidate of the run is a single move), each kind with a
// step size of its own that follows the 1/5 success rule per candidate (Kern et al. 2004): a
// success multiplies it by exp(1/d), a failure by exp(-p/(1-p)/d), so it settles where a share p of
// the candidates improve. Elitist: the best strict improvement is kept.
class Evolution final : public StrategyBase {
 public:
  Evolution(const SearchOptions& o, Configuration current, const std::string& state)
      : StrategyBase(o, std::move(current)) {
    steps_ = {o.step, o.single_step};
    if (state.empty()) return;
    const auto j = nlohmann::json::parse(state, nullptr, false);
    if (!j.is_object() || !j.contains("step") || !j.contains("single-step") || !j["step"].is_number() ||
        !j["single-step"].is_number())
      throw std::invalid_argument("strategy es: stored state '" + state + "' is not an es state");
    steps_ = {j["step"].get<double>(), j["single-step"].get<double>()};
  }
  Candidate propose(std::int64_t generation, int k) const override {
    const MoveKind kind = kind_of(generation, k);
    return make_move(current_, kind, steps_[kind == MoveKind::single], stream(o_, generation, k), k, o_);
  }
  std::string state() const override { return nlohmann::json{{"step", steps_[0]}, {"single-step", steps_[1]}}.dump(); }
  // Speculative: a generation in which nothing improves multiplies each step by the failure
  // factor once per candidate of its kind.
  bool speculative() const override { return true; }
  std::unique_ptr<Strategy> clone() const override { return std::make_unique<Evolution>(*this); }

 protected:
  int decide(std::int64_t generation, const std::vector<const Candidate*>& candidates) override {
    const double p = o_.strategy.target_success;
    const double up = std::exp(1.0 / kDamping), down = std::exp(-p / (1 - p) / kDamping);
    for (int k = 0; k < o_.lambda; ++k) {
      const MoveKind kind = kind_of(generation, k);  // the kind propose() made candidate k of
      if (kind == MoveKind::relocate) continue;      // no step: the grain goes next to the path
      const Candidate* c = candidates[static_cast<std::size_t>(k)];
      double& s = steps_[kind == MoveKind::single];
      s *= c && improves(c->eval, current_.eval, o_.objective) ? up : down;
      // Below the smallest step a jump barely changes the path; above a quarter of the box a
      // jump is a new arrangement, not a move.
      s = std::clamp(s, kMinStep, 0.25 * current_.medium.width);
    }
    return keep(generation, candidates, best_improvement(candidates));
  }

 private:
  static constexpr double kDamping = 3;
  static constexpr double kMinStep = 0.05;  // length units
  MoveKind kind_of(std::int64_t generation, int k) const {
    const std::int64_t n = (generation - 1) * o_.lambda + k + 1;  // the candidate's number in the run
    if (o_.single_every > 0 && n % o_.single_every == 0) return MoveKind::single;
    return o_.relocate_every > 0 && n % o_.relocate_every == 0 ? MoveKind::relocate : MoveKind::all;
  }
  std::vector<double> steps_;  // all-grain move, single move
};

// Late acceptance hill climbing (Burke and Bykov 2017): the generation's best passed candidate is
// kept if it is no worse than the current arrangement or than the current arrangement of
// history-length generations before, so the search walks plateaus and crosses shallow dips; the
// best so far is kept apart by the search. The paper's moves.
class LateAcceptance final : public StrategyBase {
 public:
  LateAcceptance(const SearchOptions& o, Configuration current, const std::string& state)
      : StrategyBase(o, std::move(current)) {
    const auto length = static_cast<std::size_t>(o.strategy.history_length);
    history_.assign(length, current_.eval.tortuosity);
    if (state.empty()) return;
    const auto j = nlohmann::json::parse(state, nullptr, false);
    if (!j.is_object() || !j.contains("history") || !j["history"].is_array() || j["history"].size() != length)
      throw std::invalid_argument("strategy lahc: stored state is not an lahc state of history-length " +
                                  std::to_string(length));
    for (std::size_t i = 0; i < length; ++i) {
      if (!j["history"][i].is_number()) throw std::invalid_argument("strategy lahc: stored state holds a non-number");
      history_[i] = j["history"][i].get<double>();
    }
  }
  std::string state() const override { return nlohmann::json{{"history", history_}}.dump(); }
  std::unique_ptr<Strategy> clone() const override { return std::make_unique<LateAcceptance>(*this); }

 protected:
  int decide(std::int64_t generation, const std::vector<const Candidate*>& candidates) override {
    const auto v = static_cast<std::size_t>(generation % static_cast<std::int64_t>(history_.size()));
    int k = best_passed(candidates);
    if (k >= 0) {
      const double t = candidates[static_cast<std::size_t>(k)]->eval.tortuosity;
      if (!(t >= current_.eval.tortuosity || t >= history_[v])) k = -1;
    }
    const int kept = keep(generation, candidates, k);
    history_[v] = current_.eval.tortuosity;
    return kept;
  }

 private:
  std::vector<double> history_;  // the current T of the last history-length generations, by generation mod length
};

// Simulated annealing (Kirkpatrick et al. 1983): the generation's best passed candidate is kept if
// it is no worse than the current arrangement, or else with probability exp(dT / temperature),
// the temperature halving every half-life generations; the best so far is kept apart by the
// search. The draw comes from the generation's stream lambda, which no candidate uses, so the
// state is only the current arrangement. The paper's moves.
class Annealing final : public StrategyBase {
 public:
  Annealing(const SearchOptions& o, Configuration current, const std::string& state)
      : StrategyBase(o, std::move(current)) {
    if (!state.empty() && !nlohmann::json::parse(state, nullptr, false).is_object())
      throw std::invalid_argument("strategy anneal: stored state '" + state + "' is not an anneal state");
  }
  std::string state() const override { return nlohmann::json{{"temperature", temperature_}}.dump(); }
  std::unique_ptr<Strategy> clone() const override { return std::make_unique<Annealing>(*this); }
  // As a strategy made again from its state: the temperature shows from the next generation on.
  void adopt(Configuration arrangement) override {
    current_ = std::move(arrangement);
    temperature_ = 0;
  }

 protected:
  int decide(std::int64_t generation, const std::vector<const Candidate*>& candidates) override {
    temperature_ = temperature(generation);
    int k = best_passed(candidates);
    if (k >= 0) {
      const double dt = candidates[static_cast<std::size_t>(k)]->eval.tortuosity - current_.eval.tortuosity;
      Rng rng(stream(o_, generation, o_.lambda));
      if (dt < 0 && !(rng.uniform() < std::exp(dt / temperature_))) k = -1;
    }
    return keep(generation, candidates, k);
  }

 private:
  double temperature(std::int64_t generation) const {
    return o_.strategy.temperature * std::exp2(-static_cast<double>(generation) / o_.strategy.half_life);
  }
  double temperature_ = 0;  // of the last generation told (shown in the history; not needed to resume)
};

}  // namespace

std::vector<Candidate> Strategy::propose(std::int64_t generation) const {
  std::vector<Candidate> out;
  for (int k = 0; k < options().lambda; ++k) out.push_back(propose(generation, k));
  return out;
}

int Strategy::tell(std::int64_t generation, const std::vector<Candidate>& candidates) {
  return decide(generation, detail::pointers(candidates));
}

std::unique_ptr<Strategy> Strategy::foresee(std::int64_t generation, const std::vector<const Candidate*>& evaluated,
                                            int* kept) const {
  std::unique_ptr<Strategy> told = clone();
  *kept = told->decide(generation, evaluated);
  return told;
}

bool resumes_by_replay(StrategyKind kind) { return kind == StrategyKind::cmaes; }

std::unique_ptr<Strategy> make_strategy(const SearchOptions& options, Configuration current, const std::string& state) {
  switch (options.strategy.kind) {
    case StrategyKind::paper:
      if (!state.empty()) throw std::invalid_argument("strategy paper: it keeps no state, but one is stored");
      return std::make_unique<Paper>(options, std::move(current));
    case StrategyKind::es:
      return std::make_unique<Evolution>(options, std::move(current), state);
    case StrategyKind::lahc:
      return std::make_unique<LateAcceptance>(options, std::move(current), state);
    case StrategyKind::anneal:
      return std::make_unique<Annealing>(options, std::move(current), state);
    case StrategyKind::cmaes:
      return detail::make_cmaes(options, std::move(current), state);
  }
  throw std::invalid_argument("strategy: unknown kind");
}

}  // namespace softdrop
