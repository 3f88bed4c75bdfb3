// The search strategies: their rules on evaluations made up for the test, the same history at any
// thread or lane count, a stored state that resumes bit for bit (also after SIGKILLs at random
// instants), and their options on the command line.
#include "optimizer/strategy.hpp"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "search_cli.hpp"
#include "search_fixtures.hpp"

namespace softdrop {
namespace {

// Candidates of a generation with made-up results: T > 0 passed with that T, otherwise stuck.
std::vector<Candidate> results(const Strategy& s, std::int64_t g, std::vector<double> ts) {
  std::vector<Candidate> c = s.propose(g);
  for (std::size_t k = 0; k < c.size(); ++k) {
    c[k].eval.outcome = ts[k] > 0 ? Outcome::passed : Outcome::stuck;
    c[k].eval.tortuosity = ts[k] > 0 ? ts[k] : 0;
  }
  return c;
}

TEST(Strategy, LateAcceptanceKeepsAWorseCandidateNoWorseThanLengthGenerationsAgo) {
  SearchOptions o = test::small_search_options(2);
  o.strategy.kind = StrategyKind::lahc;
  o.strategy.history_length = 3;
  const Configuration s0 = test::small_search_start(o);
  const double t0 = s0.eval.tortuosity;
  auto s = make_strategy(o, s0, "");
  EXPECT_EQ(s->tell(1, results(*s, 1, {t0 + 0.2, t0 + 0.1})), 0);  // better: kept
  EXPECT_EQ(s->current().eval.tortuosity, t0 + 0.2);
  // Worse than the current, but no worse than the current of three generations back (t0).
  EXPECT_EQ(s->tell(2, results(*s, 2, {t0 - 0.1, t0 + 0.05})), 1);
  EXPECT_EQ(s->current().eval.tortuosity, t0 + 0.05);
  EXPECT_EQ(s->tell(3, results(*s, 3, {t0 - 0.5, 0})), -1);  // worse than both: not kept
  EXPECT_EQ(s->tell(4, results(*s, 4, {0, 0})), -1);         // nothing passed
  // The state round-trips: a strategy made from it decides as this one does.
  auto again = make_strategy(o, s->current(), s->state());
  EXPECT_EQ(again->state(), s->state());
  const auto next = results(*s, 5, {t0 + 0.04, 0});
  EXPECT_EQ(again->tell(5, next), s->tell(5, next));
  EXPECT_THROW(make_strategy(o, s0, R"({"history": [1, 2]})"), std::invalid_argument);
}

TEST(Strategy, EvolutionStepsGrowWithSuccessesAndShrinkWithFailures) {
  SearchOptions o = test::small_search_options(4);
  o.strategy.kind = StrategyKind::es;
  o.strategy.target_success = 0.2;  // the classical 1/5
  o.single_every = 4;               // candidate 4 of every generation is a single move
  const Configuration s0 = test::small_search_start(o);
  const double t0 = s0.eval.tortuosity;
  auto s = make_strategy(o, s0, "");
  auto steps = [&] {
    const auto j = nlohmann::json::parse(s->state());
    return std::pair{j["step"].get<double>(), j["single-step"].get<double>()};
  };
  EXPECT_EQ(steps(), std::pair(o.step, o.single_step));
  const auto c = results(*s, 1, {t0 + 0.1, t0 + 0.2, t0 - 0.1, 0});
  EXPECT_EQ(c[3].kind, MoveKind::single);
  EXPECT_EQ(c[0].kind, MoveKind::all);
  EXPECT_EQ(s->tell(1, c), 1);  // elitist: the best strict improvement
  // All moves: 2 successes, 1 failure at p = 0.2: exp((2 - 0.25) / 3); single: 1 failure.
  EXPECT_DOUBLE_EQ(steps().first, o.step * std::exp(1.0 / 3) * std::exp(1.0 / 3) * std::exp(-0.25 / 3));
  EXPECT_DOUBLE_EQ(steps().second, o.single_step * std::exp(-0.25 / 3));
  for (int g = 2; g < 200; ++g) s->tell(g, results(*s, g, {0, 0, 0, 0}));
  EXPECT_EQ(steps().first, 0.05);  // failures shrink it to the floor, no further
  // The steps are the jump radii of its candidates (all moves: every grain within 0.05).
  const Medium& from = s->current().medium;
  const auto later = s->propose(200);
  for (std::size_t i = 0; i < from.grains.size(); ++i) {
    double dx = later[0].medium.grains[i].x - from.grains[i].x;
    if (std::abs(dx) > 0.5 * from.width) dx -= std::copysign(from.width, dx);  // across the periodic seam
    EXPECT_LE(std::hypot(dx, later[0].medium.grains[i].y - from.grains[i].y), 0.05 + 1e-12) << i;
  }
}

TEST(Strategy, ForeseeTakesTheCandidatesStillRunningToImproveOnNothing) {
  SearchOptions o = test::small_search_options(4);
  o.strategy.kind = StrategyKind::es;
  o.strategy.target_success = 0.2;
  o.single_every = 4;  // candidate 3 of every generation is a single move
  const Configuration s0 = test::small_search_start(o);
  const double t0 = s0.eval.tortuosity;
  const auto s = make_strategy(o, s0, "");
  ASSERT_TRUE(s->speculative());
  const std::string before = s->state();
  const auto c = results(*s, 1, {t0 + 0.1, t0 + 0.2, t0 - 0.1, t0 + 0.3});
  auto steps = [](const Strategy& x) {
    const auto j = nlohmann::json::parse(x.state());
    return std::pair{j["step"].get<double>(), j["single-step"].get<double>()};
  };
  const double up = std::exp(1.0 / 3), down = std::exp(-0.25 / 3);
  int kept = -2;
  // Candidates 1 and 3 still run: 0 is the best improvement so far, and 1 and 3 count as failures.
  const auto partial = s->foresee(1, {&c[0], nullptr, &c[2], nullptr}, &kept);
  EXPECT_EQ(kept, 0);
  EXPECT_EQ(partial->current().eval.tortuosity, t0 + 0.1);
  EXPECT_DOUBLE_EQ(steps(*partial).first, o.step * up * down * down);
  EXPECT_DOUBLE_EQ(steps(*partial).second, o.single_step * down);
  EXPECT_EQ(s->state(), before) << "foresee tells a copy";
  EXPECT_EQ(s->current().eval.tortuosity, t0);
  // Nothing evaluated yet: nothing kept, every step shrinks once per candidate of its kind.
  const auto none = s->foresee(1, {nullptr, nullptr, nullptr, nullptr}, &kept);
  EXPECT_EQ(kept, -1);
  EXPECT_DOUBLE_EQ(steps(*none).first, o.step * down * down * down);
  EXPECT_DOUBLE_EQ(steps(*none).second, o.single_step * down);
  // Everything evaluated: what tell() decides.
  const auto all = s->foresee(1, {&c[0], &c[1], &c[2], &c[3]}, &kept);
  const auto told = s->clone();
  EXPECT_EQ(told->tell(1, c), 3);
  EXPECT_EQ(kept, 3);
  EXPECT_EQ(all->state(), told->state());
  EXPECT_EQ(all->current().medium, c[3].medium);
  // The strategies that may keep a worse candidate cannot be foreseen from improvements alone.
  for (const StrategyKind kind : {StrategyKind::paper, StrategyKind::lahc, StrategyKind::anneal}) {
    o.strategy.kind = kind;
    EXPECT_EQ(make_strategy(o, s0, "")->speculative(), kind == StrategyKind::paper) << to_string(kind);
  }
}

TEST(Strategy, AnnealingKeepsWorseCandidatesLessOftenAsItCools) {
  SearchOptions o = test::small_search_options(2);
  o.strategy.kind = StrategyKind::anneal;
  o.strategy.temperature = 0.02;
  o.strategy.half_life = 50;
  const Configuration s0 = test::small_search_start(o);
  const double t0 = s0.eval.tortuosity;
  int hot = 0, cold = 0;
  for (int g = 1; g <= 200; ++g) {  // each generation from the start: a candidate 0.01 worse
    auto s = make_strategy(o, s0, "");
    const int kept = s->tell(g, results(*s, g, {t0 - 0.01, 0}));
    if (g <= 20) hot += kept == 0;
    if (g > 180) cold += kept == 0;
  }
  // At g <= 20 the temperature is about 0.02 (keep about exp(-0.5) = 61 %), at g > 180 about
  // 0.0017 (exp(-5.9), 0.3 %).
  EXPECT_GT(hot, 6);
  EXPECT_LE(cold, 1);
  auto s = make_strategy(o, s0, "");
  EXPECT_EQ(s->tell(1, results(*s, 1, {t0 + 0.3, t0 + 0.1})), 0);  // better: always kept
  EXPECT_NE(s->state().find("temperature"), std::string::npos);
}

std::vector<Generation> run_search(const SearchOptions& o, int generations, int threads, int lanes) {
  Search s(o, test::small_search_start(o), 0);
  std::vector<Generation> out;
  for (int g = 0; g < generations; ++g) out.push_back(s.next(threads, lanes));
  return out;
}

void expect_same(const std::vector<Generation>& a, const std::vector<Generation>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t g = 0; g < a.size(); ++g) {
    EXPECT_EQ(a[g].accepted, b[g].accepted) << g;
    EXPECT_EQ(a[g].best_t, b[g].best_t) << g;
    EXPECT_EQ(a[g].state, b[g].state) << g;
    for (std::size_t k = 0; k < a[g].candidates.size(); ++k)
      EXPECT_EQ(a[g].candidates[k].eval.tortuosity, b[g].candidates[k].eval.tortuosity) << g << " " << k;
  }
}

TEST(Strategy, EveryStrategyGivesTheSameHistoryAtAnyThreadAndLaneCount) {
  for (const StrategyKind kind : {StrategyKind::es, StrategyKind::lahc, StrategyKind::anneal, StrategyKind::cmaes}) {
    SCOPED_TRACE(to_string(kind));
    SearchOptions o = test::small_search_options(kind == StrategyKind::cmaes ? 5 : 4);
    o.strategy.kind = kind;
    const auto one = run_search(o, 8, 1, 1);
    expect_same(one, run_search(o, 8, 2, 3));
    int kept = 0;
    for (const Generation& g : one) kept += g.accepted >= 0;
    EXPECT_GT(kept, 0);
  }
}

using test::committed_generations;
using test::dump;
using test::fresh;
using test::has_run;
using test::kScene;
using test::run;
using test::spawn;
using test::wait_for;

// SIGKILLs at random instants, each followed by a resume: the history equals one that never
// stopped, and every generation committed before a kill is unchanged (the soak test's rule, for the
// strategies with a state of their own).
TEST(Strategy, KilledAtRandomInstantsEveryStrategyResumesBitForBit) {
  for (const std::string strategy : {"es", "lahc", "anneal", "cmaes"}) {
    SCOPED_TRACE(strategy);
    const std::string args = kScene + " --generations 50 --lambda " + (strategy == "cmaes" ? "5" : "4") +
                             " --threads 2 --strategy " + strategy;
    const std::string ref = fresh("strategy_ref.db"), killed = fresh("strategy_killed.db");
    ASSERT_EQ(run("optimize --db " + ref + args).code, 0);
    std::mt19937 rng(11);
    std::vector<std::pair<std::int64_t, std::string>> committed;
    for (int attempt = 0; attempt < 6; ++attempt) {
      const bool resume = has_run(killed);
      const pid_t pid = spawn("optimize --db " + killed + args + (resume ? " --resume 1" : ""));
      std::this_thread::sleep_for(
          std::chrono::milliseconds(std::uniform_int_distribution<int>(20, test::kAddressSanitizer ? 900 : 350)(rng)));
      kill(pid, SIGKILL);
      const int code = wait_for(pid);
      ASSERT_TRUE(code == -SIGKILL || code == 0) << code;
      if (const std::int64_t g = committed_generations(killed); g >= 0) committed.emplace_back(g, dump(killed, 1, g));
    }
    const auto fin = run("optimize --db " + killed + args + (has_run(killed) ? " --resume 1" : ""));
    ASSERT_EQ(fin.code, 0) << fin.err;
    for (const auto& [g, rows] : committed) EXPECT_EQ(dump(killed, 1, g), rows) << "generation " << g;
    EXPECT_EQ(dump(killed, 1), dump(ref, 1));
    // The state is stored with every generation and shown by history.
    const auto h = run("history --db " + killed + " --run 1 --format csv");
    const char* shown = strategy == "es"      ? "single-step"
                        : strategy == "lahc"  ? "history"
                        : strategy == "cmaes" ? "values"
                                              : "temperature";
    EXPECT_NE(h.out.find(shown), std::string::npos);
    EXPECT_NE(run("history --db " + killed).out.find(strategy), std::string::npos);
  }
}

TEST(StrategyCli, BadNamesUnusedOptionsAndContradictionsGetOneLine) {
  const std::string db = fresh("strategy_cli.db");
  struct Case {
    std::string args, names;
  };
  for (const Case& c :
       {Case{"--strategy tabu", "--strategy: tabu not in {paper,es,lahc,anneal,cmaes}"},
        Case{"--strategy cmaes --lambda 4", "lambda = 4: --strategy cmaes needs a population of at least 5"},
        Case{"--strategy es --sigma 3", "sigma: an option of --strategy cmaes, not used by --strategy es"},
        Case{"--strategy cmaes --lambda 6 --sigma 0", "sigma = 0: must be > 0"},
        Case{"--strategy lahc --temperature 0.1", "temperature: an option of --strategy anneal"},
        Case{"--temperature 0.3", "temperature: an option of --strategy anneal, not used by --strategy es"},
        Case{"--strategy paper --target-success 0.3",
             "target-success: an option of --strategy es, not used by --strategy paper"},
        Case{"--strategy es --history-length 9", "history-length: an option of --strategy lahc"},
        Case{"--strategy es --target-success 1.5", "target-success = 1.5: must be in (0, 1)"}}) {
    SCOPED_TRACE(c.args);
    const auto r = run("optimize --db " + db + kScene + c.args);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(db));
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3 --strategy lahc --history-length 5").code, 0);
  const std::string before = dump(db, 1);
  for (const std::string& args : {std::string(" --strategy es"), std::string(" --history-length 6")}) {
    const auto r = run("optimize --db " + db + " --resume 1 --generations 5 --quiet" + args);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("contradicts the stored run"), std::string::npos) << r.err;
  }
  EXPECT_EQ(dump(db, 1), before);
  // A run stored before strategies existed is the paper's, and --strategy paper agrees with it.
  const std::string old = fresh("strategy_old.db");
  ASSERT_EQ(
      run("optimize --db " + old + kScene + " --generations 2 --strategy paper --lambda 1 --relocate-every 0").code, 0);
  {
    SQLite::Database w(old, SQLite::OPEN_READWRITE);
    w.exec(
        "UPDATE runs SET params = json_remove(params, '$.strategy', '$.target-success', '$.history-length', "
        "'$.relocate-every')");
  }
  EXPECT_EQ(run("optimize --db " + old + " --resume 1 --generations 4 --quiet --strategy paper").code, 0);
  // Without --strategy too: the program's defaults (es, lambda 8, relocation) do not apply to it.
  EXPECT_EQ(run("optimize --db " + old + " --resume 1 --generations 6 --quiet").code, 0);
  SQLite::Database r(old, SQLite::OPEN_READONLY);
  EXPECT_EQ(r.execAndGet("SELECT count(*) FROM candidates WHERE run_id = 1").getInt(), 7);  // one a generation
  EXPECT_EQ(r.execAndGet("SELECT count(*) FROM generations WHERE run_id = 1 AND kind = 'relocate'").getInt(), 0);
}

}  // namespace
}  // namespace softdrop
