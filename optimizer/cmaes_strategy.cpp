// CMA-ES on the grain coordinates (Hansen 2006, as pagmo2's cmaes implements it), a population
// method built for noisy objectives. Each generation samples lambda arrangements from a Gaussian
// over all grain centres; their values reshape the Gaussian towards the better ones.
//
// pagmo's cmaes evolves a population through a problem it evaluates itself; the search wants to
// propose candidates, evaluate them on its own threads and lanes, and tell the values back. A
// generation's samples depend only on the algorithm's state before it (they are all drawn before
// any is evaluated), so propose() runs one generation on a copy of the algorithm against a problem
// that records what it is asked and answers 0, and tell() runs the same generation on the
// algorithm itself against a problem that answers the candidates' values in the order asked.
//
// Resume: the algorithm's state is O(n^2) numbers for n coordinates, too much to store with every
// generation. state() is the values told in the generation (and, in the first, the arrangement
// the Gaussian started on); a resumed search replays them all, which rebuilds the state bit for
// bit (the same seed, the same samples, the same values told).
#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "media/relaxation.hpp"
#include "media/spacing.hpp"
#include "strategy_base.hpp"

namespace softdrop::detail {
namespace {

// What the pagmo problem is asked and answers, shared by the copies pagmo makes of it.
struct Tape {
  std::vector<pagmo::vector_double> asked;
  std::vector<double> answers;  // in the order asked; none: every answer is 0 (sampling only)
};

// The problem pagmo sees: minimise f over [0, 1]^dim. The bounds only scale the first Gaussian
// (pagmo's D starts at the bounds' width); samples outside them are kept (no forced bounds).
struct TapedProblem {
  std::size_t dim = 0;
  std::shared_ptr<Tape> tape;
  pagmo::vector_double fitness(const pagmo::vector_double& x) const {
    const std::size_t i = tape->asked.size();
    tape->asked.push_back(x);
    if (tape->answers.empty()) return {0.0};
    if (i >= tape->answers.size()) throw std::logic_error("cmaes: asked for more values than a generation holds");
    return {tape->answers[i]};
  }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {pagmo::vector_double(dim, 0.0), pagmo::vector_double(dim, 1.0)};
  }
};

// What pagmo minimises: -T of a passed candidate; a candidate that did not pass counts as T = 1,
// the least tortuous medium there is, so the Gaussian moves away from media that clog.
double minimised(const Candidate& c) { return c.eval.outcome == Outcome::passed ? -c.eval.tortuosity : -1.0; }

// Sweeps of the spacing repair before a sample falls back to grain-by-grain moves.
constexpr int kRepairSweeps = 2000;

class Cmaes final : public StrategyBase {
 public:
  Cmaes(const SearchOptions& o, Configuration current, const std::string& state)
      : StrategyBase(o, std::move(current)),
        scale_(std::max(current_.medium.width, current_.medium.height)),
        algorithm_(1u, -1, -1, -1, -1, o.strategy.sigma / scale_, /*ftol=*/0, /*xtol=*/0, /*memory=*/true,
                   /*force_bounds=*/false, static_cast<unsigned>(derive_seed(o.seed, kStream))) {
    start_ = coordinates(current_.medium);
    if (!state.empty()) replay(state);
  }

  using StrategyBase::propose;
  Candidate propose(std::int64_t /*generation*/, int k) const override {
    pagmo::cmaes copy = algorithm_;
    const auto tape = std::make_shared<Tape>();
    copy.evolve(population(tape));
    if (tape->asked.size() != static_cast<std::size_t>(o_.lambda))
      throw std::logic_error("cmaes: a generation drew " + std::to_string(tape->asked.size()) + " samples");
    return candidate(tape->asked[static_cast<std::size_t>(k)], k);
  }

  std::string state() const override {
    if (told_ < 0) return "";
    nlohmann::json j{{"generation", told_}, {"values", values_}};
    if (told_ == first_) j["start"] = start_;
    return j.dump();
  }
  std::unique_ptr<Strategy> clone() const override { return std::make_unique<Cmaes>(*this); }

 protected:
  int decide(std::int64_t generation, const std::vector<const Candidate*>& candidates) override {
    std::vector<double> values;
    for (const Candidate* c : candidates) {
      if (!c) throw std::logic_error("cmaes: told a generation before all of it was evaluated");
      values.push_back(minimised(*c));
    }
    tell(generation, values);
    return keep(generation, candidates, best_improvement(candidates));
  }

 private:
  static constexpr std::uint64_t kStream = 0x636d61657300;  // "cmaes": pagmo's generator, apart from the moves'

  // The decision vector of a medium: x0/L, y0/L, x1/L, ... with L the longer side of the box.
  std::vector<double> coordinates(const Medium& m) const {
    std::vector<double> u;
    for (const Grain& g : m.grains) u.insert(u.end(), {g.x / scale_, g.y / scale_});
    return u;
  }

  // A population of lambda copies of the start: it sets the Gaussian's first mean; after the first
  // generation pagmo keeps its own state and uses the population only for its size.
  pagmo::population population(const std::shared_ptr<Tape>& tape) const {
    pagmo::population pop{pagmo::problem{TapedProblem{start_.size(), tape}}};
    for (int k = 0; k < o_.lambda; ++k) pop.push_back(start_, {0.0});
    return pop;
  }

  void tell(std::int64_t generation, const std::vector<double>& values) {
    const auto tape = std::make_shared<Tape>();
    tape->answers = values;
    algorithm_.evolve(population(tape));
    if (tape->asked.size() != values.size())
      throw std::logic_error("cmaes: a generation asked for " + std::to_string(tape->asked.size()) + " values");
    if (told_ < 0) first_ = generation;
    told_ = generation;
    values_ = values;
  }

  // Every generation's stored state, in order: the values told again, which rebuilds the algorithm.
  void replay(const std::string& states) {
    const auto all = nlohmann::json::parse(states, nullptr, false);
    auto bad = [](const std::string& what) {
      return std::invalid_argument("strategy cmaes: stored state " + what + " is not a cmaes state");
    };
    if (!all.is_array()) throw bad("'" + states.substr(0, 40) + "'");
    for (const auto& j : all) {
      if (!j.is_object() || !j.contains("generation") || !j["generation"].is_number_integer() ||
          !j.contains("values") || !j["values"].is_array() || j["values"].size() != static_cast<std::size_t>(o_.lambda))
        throw bad("'" + j.dump().substr(0, 40) + "'");
      const auto generation = j["generation"].get<std::int64_t>();
      if (generation <= told_) continue;  // a generation without a tell (a migration) repeats the last
      if (told_ < 0) {
        if (!j.contains("start") || !j["start"].is_array() || j["start"].size() != start_.size())
          throw bad("of generation " + std::to_string(generation) + " (no start of " + std::to_string(start_.size()) +
                    " coordinates)");
        for (std::size_t i = 0; i < start_.size(); ++i) {
          if (!j["start"][i].is_number()) throw bad("of generation " + std::to_string(generation));
          start_[i] = j["start"][i].get<double>();
        }
      }
      std::vector<double> values;
      for (const auto& v : j["values"]) {
        if (!v.is_number()) throw bad("of generation " + std::to_string(generation));
        values.push_back(v.get<double>());
      }
      tell(generation, values);
    }
  }

  // Candidate k: the sample's centres (x wrapped into a periodic box), pushed apart until the
  // spacing rule holds (relax_spacing). If the push does not settle, each grain instead moves from
  // the current arrangement to its sampled centre where the rule lets it, in index order.
  Candidate candidate(const pagmo::vector_double& u, int k) const {
    const Medium& m = current_.medium;
    Candidate c;
    c.index = k;
    c.kind = MoveKind::all;
    c.medium = m;
    auto place = [&](std::size_t i) {
      Grain g = m.grains[i];
      g.x = u[2 * i] * scale_;
      g.y = u[2 * i + 1] * scale_;
      if (m.periodic) g.x -= m.width * std::floor(g.x / m.width);
      return g;
    };
    for (std::size_t i = 0; i < m.grains.size(); ++i) c.medium.grains[i] = place(i);
    if (!relax_spacing(c.medium.grains, m.width, m.height, m.periodic, o_.gap, kRepairSweeps)) {
      double r_max = 0;
      for (const Grain& g : m.grains) r_max = std::max(r_max, g.r);
      SpacingIndex index(m.width, m.height, m.periodic, o_.gap, r_max);
      for (const Grain& g : m.grains) index.insert(g);
      for (std::size_t i = 0; i < m.grains.size(); ++i) {
        const Grain g = place(i);
        if (index.can_move(static_cast<int>(i), g)) index.move(static_cast<int>(i), g);
        c.medium.grains[i] = index.grain(static_cast<int>(i));
      }
    }
    if (auto bad = find_spacing_violation(c.medium, o_.gap))
      throw std::logic_error("cmaes: grains " + std::to_string(bad->first) + " and " + std::to_string(bad->second) +
                             " break the spacing rule after the repair");
    for (std::size_t i = 0; i < m.grains.size(); ++i) c.moved += !(c.medium.grains[i] == m.grains[i]);
    return c;
  }

  double scale_;                // L: length units per unit of the decision vector
  pagmo::cmaes algorithm_;      // its state after the last generation told
  std::vector<double> start_;   // the decision vector the Gaussian started on
  std::int64_t first_ = -1;     // the first generation told, -1: none yet
  std::int64_t told_ = -1;      // the last generation told
  std::vector<double> values_;  // its values, as told (minimised)
};

}  // namespace

std::unique_ptr<Strategy> make_cmaes(const SearchOptions& options, Configuration current, const std::string& state) {
  return std::make_unique<Cmaes>(options, std::move(current), state);
}

}  // namespace softdrop::detail
