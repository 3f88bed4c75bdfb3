// The search: evaluation of a candidate, generation 0, and one generation at a time (its candidates
// in parallel), keeping the best strict improvement. The speculating drive is in
// speculative_pipeline.cpp and drive.cpp.
#include "softdrop/search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "evaluation.hpp"
#include "media/spacing.hpp"
#include "strategy.hpp"
#include "util/enum_names.hpp"
#include "util/validation.hpp"

namespace softdrop {
using detail::as_evaluation;
using detail::evaluation_run;
using detail::fail;
using detail::num;

constexpr detail::EnumName<MoveKind> kMoveKinds[] = {{MoveKind::initial, "initial"}, {MoveKind::all, "all"},
                                                     {MoveKind::single, "single"},   {MoveKind::relocate, "relocate"},
                                                     {MoveKind::migrate, "migrate"}, {MoveKind::mixed, "mixed"}};
constexpr detail::EnumName<Termination> kTerminations[] = {{Termination::generations, "generations"},
                                                           {Termination::time_limit, "time-limit"},
                                                           {Termination::interrupted, "interrupted"},
                                                           {Termination::callback, "callback"}};
constexpr detail::EnumName<StrategyKind> kStrategies[] = {{StrategyKind::paper, "paper"},
                                                          {StrategyKind::es, "es"},
                                                          {StrategyKind::lahc, "lahc"},
                                                          {StrategyKind::anneal, "anneal"},
                                                          {StrategyKind::cmaes, "cmaes"}};

const char* to_string(MoveKind kind) { return detail::name_of(kMoveKinds, kind); }

MoveKind parse_move_kind(const std::string& name) { return detail::parse_name(kMoveKinds, name, "move kind"); }

const char* to_string(Termination termination) { return detail::name_of(kTerminations, termination); }

const char* to_string(StrategyKind kind) { return detail::name_of(kStrategies, kind); }

StrategyKind parse_strategy(const std::string& name) { return detail::parse_name(kStrategies, name, "strategy"); }

std::vector<std::string> strategy_names() { return detail::name_list(kStrategies); }

bool StrategyOptions::IsValid(std::string* why) const {
  if (!(target_success > 0 && target_success < 1))
    return fail(why, "target-success = " + num(target_success) + ": must be in (0, 1)");
  if (history_length < 1 || history_length > 100'000)
    return fail(why, "history-length = " + std::to_string(history_length) + ": must be in [1, 1e5]");
  if (!(temperature > 0) || !std::isfinite(temperature))
    return fail(why, "temperature = " + num(temperature) + ": must be > 0");
  if (!(half_life > 0) || !std::isfinite(half_life))
    return fail(why, "half-life = " + num(half_life) + ": must be > 0");
  if (!(sigma > 0) || !std::isfinite(sigma)) return fail(why, "sigma = " + num(sigma) + ": must be > 0");
  return true;
}

bool SearchOptions::IsValid(std::string* why) const {
  if (lambda < 1 || lambda > 4096) return fail(why, "lambda = " + std::to_string(lambda) + ": must be in [1, 4096]");
  if (strategy.kind == StrategyKind::cmaes && lambda < 5)
    return fail(why, "lambda = " + std::to_string(lambda) + ": --strategy cmaes needs a population of at least 5");
  if (single_every < 0) return fail(why, "single-every = " + std::to_string(single_every) + ": must be >= 0");
  if (relocate_every < 0) return fail(why, "relocate-every = " + std::to_string(relocate_every) + ": must be >= 0");
  if (!std::isfinite(step) || step <= 0) return fail(why, "step = " + num(step) + ": must be > 0");
  if (!std::isfinite(single_step) || single_step <= 0)
    return fail(why, "single-step = " + num(single_step) + ": must be > 0");
  if (max_redraws < 0 || max_redraws > 1'000'000)
    return fail(why, "max-redraws = " + std::to_string(max_redraws) + ": must be in [0, 1e6]");
  if (!std::isfinite(gap) || gap < 0) return fail(why, "gap = " + num(gap) + ": must be >= 0");
  if (!strategy.IsValid(why)) return false;
  if (!objective.IsValid(why)) return false;
  if (!droplet.IsValid(why)) return false;
  if (!run.IsValid(why)) return false;
  if (run.path_interval < 1)
    return fail(why, "path-interval = " + std::to_string(run.path_interval) + ": must be >= 1");
  return true;
}

namespace detail {
bool improves(const Evaluation& e, const Evaluation& parent, const ObjectiveOptions& objective) {
  if (!objective.robust() || parent.values.size() != e.values.size()) return improves(e, parent.tortuosity);
  if (!improves(e, parent.tortuosity)) return false;
  const double n = static_cast<double>(e.values.size());
  double mean = 0;
  for (std::size_t j = 0; j < e.values.size(); ++j) mean += e.values[j] - parent.values[j];
  mean /= n;
  double ss = 0;
  for (std::size_t j = 0; j < e.values.size(); ++j) {
    const double d = e.values[j] - parent.values[j] - mean;
    ss += d * d;
  }
  const double se = n > 1 ? std::sqrt(ss / (n - 1) / n) : 0.0;
  return e.tortuosity - parent.tortuosity > objective.margin * se;
}

int best_improvement(const std::vector<const Candidate*>& candidates, const Evaluation& parent,
                     const ObjectiveOptions& objective) {
  int best = -1;
  for (const Candidate* c : candidates)
    if (c && improves(c->eval, parent, objective) &&
        (best < 0 || c->eval.tortuosity > candidates[static_cast<std::size_t>(best)]->eval.tortuosity))
      best = c->index;
  return best;
}

RunOptions evaluation_run(const RunOptions& run) {
  RunOptions r = run;
  r.area_interval = 0;
  r.snapshot_times.clear();
  return r;
}

Evaluation as_evaluation(RunSummary&& s, std::chrono::steady_clock::time_point t0) {
  Evaluation e;
  e.outcome = s.outcome;
  e.reason = std::move(s.reason);
  e.tortuosity = s.outcome == Outcome::passed ? s.tortuosity : 0.0;
  e.steps = s.steps;
  e.touched = std::move(s.touched);
  e.path_x = std::move(s.path_x);
  e.path_y = std::move(s.path_y);
  e.droplets = 1;
  e.passed = e.outcome == Outcome::passed ? 1 : 0;
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

Evaluation as_evaluation(const ObjectiveOptions& objective, std::vector<RunSummary>&& runs,
                         std::chrono::steady_clock::time_point t0) {
  if (!objective.robust()) return as_evaluation(std::move(runs.at(0)), t0);
  Evaluation e;
  e.droplets = static_cast<int>(runs.size());
  const RunSummary* failed = nullptr;
  for (const RunSummary& r : runs) {
    e.steps += r.steps;
    e.touched.insert(e.touched.end(), r.touched.begin(), r.touched.end());
    if (r.outcome == Outcome::passed)
      ++e.passed;
    else if (!failed)
      failed = &r;
  }
  std::sort(e.touched.begin(), e.touched.end());
  e.touched.erase(std::unique(e.touched.begin(), e.touched.end()), e.touched.end());
  e.outcome = e.passed > 0 ? Outcome::passed : runs.front().outcome;
  if (failed)
    e.reason = std::to_string(e.droplets - e.passed) + " of " + std::to_string(e.droplets) +
               " droplets did not pass (the first: " + to_string(failed->outcome) + ", " + failed->reason + ")";
  e.tortuosity = objective_value(objective, runs);
  for (const RunSummary& r : runs) e.values.push_back(r.outcome == Outcome::passed ? r.tortuosity : 1.0);
  e.path_x = std::move(runs.front().path_x);
  e.path_y = std::move(runs.front().path_y);
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}
}  // namespace detail

Evaluation evaluate(const Medium& medium, const SearchOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(options.droplet, medium);
  return as_evaluation(sim.run(0.5 * medium.width, evaluation_run(options.run)), t0);
}

Evaluation evaluate(const Medium& medium, const SearchOptions& options, std::int64_t generation) {
  if (!options.objective.robust()) return evaluate(medium, options);
  std::vector<Candidate> one(1);
  one[0].medium = medium;
  detail::evaluate_candidates(one, options, generation, 1, 0);
  return std::move(one[0].eval);
}

namespace {
void check_medium(const Medium& medium, const SearchOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (!medium.IsValid(&why)) throw std::invalid_argument(why);
  if (medium.grains.empty()) throw std::invalid_argument("medium: the search needs at least one grain");
  if (options.step >= 0.5 * medium.width)
    throw std::invalid_argument("step = " + num(options.step) + ": must be < half the width");
  if (options.single_step >= 0.5 * medium.width)
    throw std::invalid_argument("single-step = " + num(options.single_step) + ": must be < half the width");
  if (auto bad = find_spacing_violation(medium, options.gap))
    throw std::invalid_argument(bad->first == bad->second
                                    ? "medium: grain " + std::to_string(bad->first) +
                                          " is not wholly inside the box in y (the search keeps r <= y <= height - r)"
                                    : "medium: grains " + std::to_string(bad->first) + " and " +
                                          std::to_string(bad->second) +
                                          " are closer than the spacing rule allows (gap " + num(options.gap) + ")");
}
}  // namespace

Generation initial_generation(const Medium& medium, const SearchOptions& options, Configuration* best) {
  check_medium(medium, options);
  const auto t0 = std::chrono::steady_clock::now();
  Generation g;
  g.number = 0;
  g.kind = MoveKind::initial;
  Candidate c;
  c.kind = MoveKind::initial;
  c.medium = medium;
  c.eval = evaluate(medium, options, 0);
  if (c.eval.outcome != Outcome::passed)
    throw std::runtime_error(std::string("the droplet does not pass through the starting medium: ") +
                             to_string(c.eval.outcome) + " (" + c.eval.reason + ")");
  best->generation = 0;
  best->medium = medium;
  best->eval = c.eval;
  g.accepted = 0;
  g.best_t = c.eval.tortuosity;
  g.touched = static_cast<int>(c.eval.touched.size());
  g.candidates.push_back(std::move(c));
  g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

Search::Search(const SearchOptions& options, Configuration best, std::int64_t last_generation)
    : Search(options, best, best, "", last_generation) {}

Search::Search(const SearchOptions& options, Configuration best, Configuration current, const std::string& state,
               std::int64_t last_generation)
    : options_(options), best_(std::move(best)), last_(last_generation) {
  check_medium(best_.medium, options_);
  if (best_.eval.outcome != Outcome::passed)
    throw std::invalid_argument("search: the best configuration's droplet did not pass");
  if (current.eval.outcome != Outcome::passed)
    throw std::invalid_argument("search: the current configuration's droplet did not pass");
  if (last_ < 0) throw std::invalid_argument("search: last generation " + std::to_string(last_) + " < 0");
  if (options_.objective.robust()) {
    if (best_.generation != current.generation || best_.generation > last_)
      throw std::invalid_argument("search: with the " + std::string(to_string(options_.objective.kind)) +
                                  " objective the best is the current arrangement (generation " +
                                  std::to_string(current.generation) + "), not generation " +
                                  std::to_string(best_.generation));
    remeasured_ = last_ - best_.generation;
  }
  strategy_ = make_strategy(options_, std::move(current), state);
}

Search::~Search() = default;
Search::Search(Search&&) noexcept = default;
Search& Search::operator=(Search&&) noexcept = default;

Generation Search::next(int threads, int lanes) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Candidate> candidates = strategy_->propose(last_ + 1);
  const bool robust = options_.objective.robust();
  if (robust) {  // the parent runs on the candidates' starts, in the same batch
    Candidate parent;
    parent.index = options_.lambda;
    parent.medium = strategy_->current().medium;
    candidates.push_back(std::move(parent));
  }
  detail::evaluate_candidates(candidates, options_, last_ + 1, threads, lanes);
  Evaluation parent;
  if (robust) {
    parent = std::move(candidates.back().eval);
    candidates.pop_back();
  }
  return complete(std::move(candidates), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                  std::move(parent));
}

Generation Search::complete(std::vector<Candidate> candidates, double seconds, Evaluation parent) {
  if (options_.objective.robust()) return complete_robust(std::move(candidates), seconds, std::move(parent));
  Generation g = open_generation(std::move(candidates));
  g.accepted = strategy_->tell(g.number, g.candidates);
  // The best so far is always an arrangement the strategy kept (and so the history stored).
  const int best_k = detail::best_improvement(detail::pointers(g.candidates), best_.eval.tortuosity);
  if (best_k >= 0) {
    if (best_k != g.accepted)
      throw std::logic_error("search strategy " + std::string(to_string(options_.strategy.kind)) + ": generation " +
                             std::to_string(g.number) + " improved the best with candidate " + std::to_string(best_k) +
                             " but kept " + std::to_string(g.accepted));
    const Candidate& c = g.candidates[static_cast<std::size_t>(best_k)];
    best_.generation = g.number;
    best_.medium = c.medium;
    best_.eval = c.eval;
  }
  close_generation(g, seconds);
  return g;
}

Generation Search::complete_robust(std::vector<Candidate> candidates, double seconds, Evaluation parent) {
  Generation g = open_generation(std::move(candidates));
  if (parent.droplets != options_.objective.starts)
    throw std::logic_error("Search::complete: the parent was not run on the generation's starts");
  // Every value of this generation is on the same starts: the candidates compete with the parent's
  // value here, not with the value it was kept with (which won a draw on other starts).
  const double fresh = parent.tortuosity;
  strategy_->remeasure(fresh, parent.values);
  g.accepted = strategy_->tell(g.number, g.candidates);
  if (g.accepted >= 0) {
    const Candidate& c = g.candidates[static_cast<std::size_t>(g.accepted)];
    best_ = Configuration{g.number, c.medium, c.eval};
    remeasured_ = 0;
  } else {
    rerun_best(fresh);
  }
  close_generation(g, seconds);
  g.parent = std::move(parent);
  return g;
}

Generation Search::immigrate(const Configuration& immigrant) {
  Generation g;
  g.number = last_ + 1;
  g.kind = MoveKind::migrate;
  Candidate c;
  c.kind = MoveKind::migrate;
  c.medium = immigrant.medium;
  c.eval = immigrant.eval;
  const Medium& own = strategy_->current().medium;
  for (std::size_t i = 0; i < c.medium.grains.size(); ++i)
    if (i >= own.grains.size() || !(c.medium.grains[i] == own.grains[i])) ++c.moved;
  bool better = false;
  if (options_.objective.robust()) {
    // Two islands' values come from different starts: the immigrant and this island's arrangement
    // run again on this generation's starts, and the immigrant must beat it there.
    std::vector<Candidate> both(2);
    both[0].medium = c.medium;
    both[1].index = 1;
    both[1].medium = own;
    detail::evaluate_candidates(both, options_, g.number, 1, 0);
    c.eval = std::move(both[0].eval);
    g.parent = std::move(both[1].eval);
    strategy_->remeasure(g.parent.tortuosity, g.parent.values);
    better = detail::improves(c.eval, strategy_->current().eval, options_.objective);
    if (!better) rerun_best(g.parent.tortuosity);
  } else {
    better = immigrant.eval.outcome == Outcome::passed && immigrant.eval.tortuosity > best_.eval.tortuosity;
  }
  if (better) {
    g.accepted = 0;
    best_ = Configuration{g.number, c.medium, c.eval};
    remeasured_ = 0;
    strategy_->adopt(best_);
  }
  g.candidates.push_back(std::move(c));
  close_generation(g, 0);
  return g;
}

Generation Search::open_generation(std::vector<Candidate> candidates) const {
  Generation g;
  g.number = last_ + 1;
  g.candidates = std::move(candidates);
  // The generation's kind is its candidates' move, or mixed where they differ (es draws each
  // candidate's move on its own), so that grouping generations by kind groups like moves.
  g.kind = g.candidates.empty() ? move_kind(g.number, options_) : g.candidates.front().kind;
  for (const Candidate& c : g.candidates)
    if (c.kind != g.kind) g.kind = MoveKind::mixed;
  if (static_cast<int>(g.candidates.size()) != options_.lambda)
    throw std::logic_error("Search::complete: " + std::to_string(g.candidates.size()) + " candidates for lambda " +
                           std::to_string(options_.lambda));
  return g;
}

void Search::close_generation(Generation& g, double seconds) {
  last_ = g.number;
  g.best_t = best_.eval.tortuosity;
  g.touched = static_cast<int>(best_.eval.touched.size());
  g.seconds = seconds;
  g.state = strategy_->state();
}

void Search::rerun_best(double fresh) {
  // The running mean of the re-runs: the value the best was kept with is dropped at the first.
  ++remeasured_;
  best_.eval.tortuosity += (fresh - best_.eval.tortuosity) / static_cast<double>(remeasured_);
}

}  // namespace softdrop
