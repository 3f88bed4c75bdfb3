// The robust objectives: their starts, their values over K droplets, and a search on them that
// compares every candidate with its parent re-run on the same fresh starts, deterministically at
// any thread count and through a resume.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "optimizer/evaluation.hpp"
#include "optimizer/strategy.hpp"
#include "search_fixtures.hpp"
#include "softdrop/search.hpp"
#include "store/params_json.hpp"

namespace softdrop {
namespace {

SearchOptions robust_options(ObjectiveKind kind, int starts = 6, int lambda = 3) {
  SearchOptions o = test::small_search_options(lambda);
  o.objective.kind = kind;
  o.objective.starts = starts;
  return o;
}

RunSummary run_of(Outcome outcome, double t) {
  RunSummary r;
  r.outcome = outcome;
  r.tortuosity = t;
  return r;
}

TEST(Objective, SingleStartsAtTheMiddleOfTheTop) {
  const Medium m = test::small_search_medium();
  ObjectiveOptions single;
  EXPECT_EQ(objective_starts(single, 7, 3, m, test::balloon_droplet()), std::vector<double>{80.0});
}

TEST(Objective, RobustStartsAreStratifiedFreshEachGenerationAndReproducible) {
  Medium m = test::small_search_medium();
  ObjectiveOptions o;
  o.kind = ObjectiveKind::mean;
  o.starts = 8;
  const DropletParams d = test::balloon_droplet();
  const std::vector<double> a = objective_starts(o, 7, 3, m, d);
  ASSERT_EQ(a.size(), 8u);
  for (std::size_t j = 0; j < a.size(); ++j) {  // droplet j in the j-th eighth of [0, W)
    EXPECT_GE(a[j], 20.0 * static_cast<double>(j));
    EXPECT_LT(a[j], 20.0 * static_cast<double>(j + 1));
  }
  EXPECT_EQ(objective_starts(o, 7, 3, m, d), a);
  const std::vector<double> next = objective_starts(o, 7, 4, m, d), other_seed = objective_starts(o, 8, 3, m, d);
  for (std::size_t j = 0; j < a.size(); ++j) {
    EXPECT_NE(next[j], a[j]);
    EXPECT_NE(other_seed[j], a[j]);
  }
  m.periodic = false;  // walls: the droplet's centre stays a radius from either wall
  for (double x : objective_starts(o, 7, 3, m, d)) {
    EXPECT_GE(x, d.radius);
    EXPECT_LE(x, m.width - d.radius);
  }
}

TEST(Objective, ValuesCountADropletThatDidNotPassAsAStraightPath) {
  const std::vector<RunSummary> runs = {run_of(Outcome::passed, 1.5), run_of(Outcome::stuck, 9.0),
                                        run_of(Outcome::passed, 2.0), run_of(Outcome::timeout, 0.0)};
  ObjectiveOptions o;
  o.kind = ObjectiveKind::mean;
  EXPECT_DOUBLE_EQ(objective_value(o, runs), (1.5 + 1 + 2.0 + 1) / 4);
  o.kind = ObjectiveKind::quantile;  // sorted 1, 1, 1.5, 2; numpy's linear quantile
  o.quantile = 0.25;
  EXPECT_DOUBLE_EQ(objective_value(o, runs), 1.0);
  o.quantile = 0.75;  // h = 2.25: 1.5 + 0.25 x 0.5
  EXPECT_DOUBLE_EQ(objective_value(o, runs), 1.625);
  o.kind = ObjectiveKind::lower_bound;
  o.se_factor = 2;
  // deviations from 1.375: 0.125, -0.375, 0.625, -0.375; squares sum to 0.6875
  EXPECT_NEAR(objective_value(o, runs), 1.375 - 2 * std::sqrt(0.6875 / 3) / 2, 1e-15);
  // A medium that traps every droplet scores 1, below any medium a droplet passes.
  o.kind = ObjectiveKind::mean;
  EXPECT_EQ(objective_value(o, {run_of(Outcome::stuck, 0), run_of(Outcome::stuck, 0)}), 1.0);
  // single: the one droplet's T, or 0 when it did not pass, as the paper's search always scored.
  EXPECT_EQ(objective_value(ObjectiveOptions{}, {run_of(Outcome::stuck, 3.0)}), 0.0);
}

TEST(Objective, OptionsRefuseWhatHasNoMeaning) {
  std::string why;
  ObjectiveOptions o;
  o.starts = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("starts = 0"), std::string::npos) << why;
  o.starts = kMaxObjectiveStarts + 1;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  for (double q : {0.0, 1.0, -0.5, std::nan("")}) {
    o.quantile = q;
    EXPECT_FALSE(o.IsValid(&why)) << q;
    EXPECT_NE(why.find("quantile"), std::string::npos) << why;
  }
  o = {};
  o.margin = -1;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.se_factor = INFINITY;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THROW(parse_objective("median"), std::invalid_argument);
}

TEST(Objective, AStoredRunWithoutTheKeysReadsAsTheSingleObjective) {
  SearchOptions o = robust_options(ObjectiveKind::quantile, 12);
  o.objective.quantile = 0.1;
  const SearchOptions back = search_params_from_json(search_params_to_json(o));
  EXPECT_EQ(back.objective.kind, ObjectiveKind::quantile);
  EXPECT_EQ(back.objective.starts, 12);
  EXPECT_EQ(back.objective.quantile, 0.1);
  nlohmann::json j = nlohmann::json::parse(search_params_to_json(o));
  for (const char* key : {"objective", "starts", "quantile", "se-factor", "margin"}) j.erase(key);
  EXPECT_EQ(search_params_from_json(j.dump()).objective.kind, ObjectiveKind::single);
}

TEST(Objective, AnEvaluationIsItsDropletsRunAlone) {
  const SearchOptions o = robust_options(ObjectiveKind::mean, 5);
  const Medium m = test::small_search_medium();
  int all_passed = 0;
  for (std::int64_t g = 0; g < 4; ++g) {
    SCOPED_TRACE("generation " + std::to_string(g));
    const Evaluation e = evaluate(m, o, g);
    ASSERT_EQ(e.droplets, 5);
    ASSERT_EQ(e.values.size(), 5u);
    const std::vector<double> starts = objective_starts(o.objective, o.seed, g, m, o.droplet);
    std::set<std::int32_t> touched;
    double sum = 0;
    int passed = 0;
    for (std::size_t j = 0; j < starts.size(); ++j) {
      Simulation sim(o.droplet, m);
      const RunSummary r = sim.run(starts[j], detail::evaluation_run(o.run));
      EXPECT_EQ(e.values[j], r.outcome == Outcome::passed ? r.tortuosity : 1.0) << "droplet " << j;
      sum += e.values[j];
      passed += r.outcome == Outcome::passed;
      touched.insert(r.touched.begin(), r.touched.end());
    }
    EXPECT_EQ(e.passed, passed);
    EXPECT_EQ(e.outcome == Outcome::passed, passed > 0);
    EXPECT_DOUBLE_EQ(e.tortuosity, sum / 5);
    EXPECT_EQ(e.touched, std::vector<std::int32_t>(touched.begin(), touched.end()));
    all_passed += passed;
  }
  EXPECT_GT(all_passed, 0);  // (the scene lets some droplets through)
}

// A candidate beats its parent only by more than `margin` standard errors of the paired
// differences; with margin 0, by any gain.
TEST(Objective, ACandidateMustBeatItsParentBeyondTheNoise) {
  ObjectiveOptions o;
  o.kind = ObjectiveKind::mean;
  Evaluation parent, c;
  parent.outcome = c.outcome = Outcome::passed;
  parent.values = {1.0, 1.2, 1.4, 1.6};
  c.values = {1.1, 1.1, 1.6, 1.8};  // differences 0.1, -0.1, 0.2, 0.2: mean 0.1, SE 0.0707
  parent.tortuosity = 1.3;
  c.tortuosity = 1.4;
  o.margin = 1;
  EXPECT_TRUE(detail::improves(c, parent, o));
  o.margin = 2;
  EXPECT_FALSE(detail::improves(c, parent, o));
  o.margin = 0;
  EXPECT_TRUE(detail::improves(c, parent, o));
  c.tortuosity = parent.tortuosity;
  EXPECT_FALSE(detail::improves(c, parent, o));
}

struct RobustHistory {
  std::vector<Generation> history;
  Configuration best;
};
RobustHistory robust_run(const SearchOptions& o, int generations, int threads) {
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search s(o, best, 0);
  RobustHistory r;
  for (int i = 0; i < generations; ++i) r.history.push_back(s.next(threads));
  r.best = s.best();
  return r;
}

TEST(Objective, TheRobustSearchReRunsItsParentAndKeepsTheMeanOfTheReRunsAsItsBest) {
  SearchOptions o = robust_options(ObjectiveKind::mean, 6, 3);
  o.objective.margin = 0;  // accept often, to see both branches in a few generations
  const RobustHistory r = robust_run(o, 8, 2);
  int accepted = 0;
  double mean = 0;
  int reruns = 0;
  for (const Generation& g : r.history) {
    SCOPED_TRACE("generation " + std::to_string(g.number));
    ASSERT_EQ(g.parent.droplets, 6);
    for (const Candidate& c : g.candidates) EXPECT_EQ(c.eval.droplets, 6);
    if (g.accepted >= 0) {
      ++accepted;
      const Candidate& kept = g.candidates[static_cast<std::size_t>(g.accepted)];
      EXPECT_GT(kept.eval.tortuosity, g.parent.tortuosity);  // it beat the parent on the same starts
      EXPECT_EQ(g.best_t, kept.eval.tortuosity);
      reruns = 0;
    } else {
      const double fresh = g.parent.tortuosity;
      mean = reruns == 0 ? fresh : mean + (fresh - mean) / (reruns + 1);
      ++reruns;
      EXPECT_DOUBLE_EQ(g.best_t, mean);
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_LT(accepted, 8);
  // Threads change nothing.
  const RobustHistory one = robust_run(o, 8, 1);
  for (std::size_t i = 0; i < r.history.size(); ++i) {
    EXPECT_EQ(one.history[i].accepted, r.history[i].accepted);
    EXPECT_EQ(one.history[i].best_t, r.history[i].best_t);
    EXPECT_EQ(one.history[i].parent.tortuosity, r.history[i].parent.tortuosity);
  }
}

TEST(Objective, ARobustSearchResumedFromItsStoredStateGoesOnBitForBit) {
  SearchOptions o = robust_options(ObjectiveKind::lower_bound, 5, 2);
  o.strategy.kind = StrategyKind::es;
  o.objective.margin = 0.5;
  const RobustHistory whole = robust_run(o, 10, 2);
  const RobustHistory first = robust_run(o, 5, 2);
  // What a resume has: the last kept arrangement with its evaluation on the starts it was kept
  // on, the stored best_t and the strategy's state.
  Configuration current = first.best;
  current.eval = evaluate(current.medium, o, current.generation);
  Configuration best = current;
  best.eval.tortuosity = first.history.back().best_t;
  Search resumed(o, best, current, first.history.back().state, 5);
  for (int g = 6; g <= 10; ++g) {
    const Generation x = resumed.next(1);
    const Generation& y = whole.history[static_cast<std::size_t>(g - 1)];
    EXPECT_EQ(x.accepted, y.accepted) << g;
    EXPECT_EQ(x.best_t, y.best_t) << g;
    EXPECT_EQ(x.state, y.state) << g;
    EXPECT_EQ(x.parent.tortuosity, y.parent.tortuosity) << g;
  }
  EXPECT_EQ(resumed.best().medium, whole.best.medium);
}

TEST(Objective, AnImmigrantMustBeatTheIslandsArrangementOnTheSameStarts) {
  SearchOptions o = robust_options(ObjectiveKind::mean, 4, 2);
  o.objective.margin = 0;
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search s(o, best, 0);
  s.next(1);
  // Itself as an immigrant: the same values on the same starts, so never strictly better.
  const Generation same = s.immigrate(s.best());
  EXPECT_EQ(same.accepted, -1);
  ASSERT_EQ(same.parent.droplets, 4);
  EXPECT_EQ(same.candidates.at(0).eval.values, same.parent.values);
  EXPECT_EQ(same.candidates.at(0).eval.tortuosity, same.parent.tortuosity);
  EXPECT_EQ(same.best_t, s.best().eval.tortuosity);
}

TEST(Objective, ARobustDriveEvaluatesOneGenerationAtATime) {
  const SearchOptions o = robust_options(ObjectiveKind::mean, 4, 2);
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search s(o, best, 0);
  DriveOptions d;
  d.generations = 2;
  d.threads = 2;
  const SearchSummary summary = drive(s, d, nullptr);
  EXPECT_EQ(summary.speculation.threads, 0);  // the K droplets fill the threads instead
  EXPECT_EQ(summary.droplets, 2 * (2 * 4 + 4));
}

}  // namespace
}  // namespace softdrop
