// The search: generations are deterministic at any thread count, the best never gets worse and is
// only replaced by a strictly better passing candidate; the drive's lanes, stops, resumption and
// refusals. (The speculating drive: search_speculation_test.cpp.)
#include "softdrop/search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "fixtures.hpp"
#include "media/spacing.hpp"
#include "optimizer/drive_test_seam.hpp"
#include "search_fixtures.hpp"
#include "search_reference.hpp"
#include "sim/lane_policy.hpp"
#include "store/params_json.hpp"

namespace softdrop {
namespace {

using test::drive_as;
using test::drive_recorded;
using test::Driven;
using test::expect_same_history;
using test::one_at_a_time;
using test::Reference;

TEST(Search, BestNeverDropsAndOnlyStrictImprovementsOfPassingCandidatesAreKept) {
  const SearchOptions o = test::small_search_options(2);
  Configuration best;
  const Generation g0 = initial_generation(test::small_search_medium(), o, &best);
  EXPECT_EQ(g0.accepted, 0);
  Search search(o, best, 0);
  double previous = best.eval.tortuosity;
  int accepted = 0;
  for (int i = 0; i < 24; ++i) {
    const Generation g = search.next(2);
    ASSERT_EQ(g.number, i + 1);
    ASSERT_EQ(g.candidates.size(), 2u);
    EXPECT_GE(g.best_t, previous);
    double top = previous;
    int expect = -1;
    for (const Candidate& c : g.candidates) {
      EXPECT_FALSE(find_spacing_violation(c.medium, o.gap).has_value());
      if (c.eval.outcome == Outcome::passed && c.eval.tortuosity > top) top = c.eval.tortuosity, expect = c.index;
    }
    EXPECT_EQ(g.accepted, expect);
    if (g.accepted >= 0) {
      ++accepted;
      EXPECT_GT(g.best_t, previous);
      EXPECT_EQ(search.best().generation, g.number);
      // The stored fitness is the configuration's: a fresh evaluation gives it bit for bit.
      const Evaluation again = evaluate(search.best().medium, o);
      EXPECT_EQ(again.tortuosity, search.best().eval.tortuosity);
      EXPECT_EQ(again.touched, search.best().eval.touched);
    } else {
      EXPECT_EQ(g.best_t, previous);
    }
    previous = g.best_t;
  }
  EXPECT_GT(accepted, 0) << "24 generations of this scene always find an improvement";
  EXPECT_GT(search.best().eval.tortuosity, best.eval.tortuosity);
}

TEST(Search, LambdaFourGivesTheSameHistoryOnOneAndTwoThreads) {
  const SearchOptions o = test::small_search_options(4);
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search one(o, best, 0), two(o, best, 0);
  for (int i = 0; i < 6; ++i) {
    const Generation a = one.next(1), b = two.next(2);
    ASSERT_EQ(a.accepted, b.accepted);
    ASSERT_EQ(a.best_t, b.best_t);
    for (std::size_t k = 0; k < a.candidates.size(); ++k) {
      EXPECT_EQ(a.candidates[k].medium, b.candidates[k].medium);
      EXPECT_EQ(a.candidates[k].eval.outcome, b.candidates[k].eval.outcome);
      EXPECT_EQ(a.candidates[k].eval.tortuosity, b.candidates[k].eval.tortuosity);
      EXPECT_EQ(a.candidates[k].eval.steps, b.candidates[k].eval.steps);
    }
  }
  EXPECT_EQ(one.best().medium, two.best().medium);
}

TEST(Search, DefaultLanesKeepTheCandidatesInFlightOfTwoThreads) {
  // 8 lanes on 1 and 2 threads; more threads share 2 threads' candidates. With SSE2 alone, where
  // the droplets step one at a time, one lane: one thread then evaluates one candidate at a time
  // and does not speculate. At the widths this processor has.
  test::LackedWidths lacked;
  for (VectorWidth width : {VectorWidth::avx512, VectorWidth::avx, VectorWidth::sse2}) {
    const test::VectorWidthLimit limit(width);
    if (!lacked.has(limit, width)) continue;
    SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(width)));
    for (auto [lambda, threads, wide_lanes] :
         {std::tuple{1, 1, 8}, std::tuple{1, 2, 8}, std::tuple{1, 3, 5}, std::tuple{1, 4, 4}, std::tuple{1, 16, 1},
          std::tuple{2, 1, 8}, std::tuple{2, 2, 8}, std::tuple{2, 3, 5}, std::tuple{2, 4, 4}, std::tuple{4, 1, 8},
          std::tuple{8, 1, 8}, std::tuple{8, 2, 8}, std::tuple{4, 16, 1}}) {
      SCOPED_TRACE("lambda " + std::to_string(lambda) + ", " + std::to_string(threads) + " threads");
      const SearchOptions o = test::small_search_options(lambda);
      Search s(o, test::small_search_start(o), 0);
      DriveOptions d;
      d.generations = 1;
      d.threads = threads;
      const SearchSummary sum = drive(s, d, nullptr);
      const int lanes = width >= VectorWidth::avx ? wide_lanes : 1;
      const bool speculates = lanes > 1 || threads > 1;
      EXPECT_EQ(sum.speculation.threads, speculates ? threads : 0);
      EXPECT_EQ(sum.speculation.lanes, speculates ? lanes : 0);
    }
    // With AVX-512 or AVX, red-black candidates are stepped in blocks too: the same lanes, except
    // with AVX at lambda 1 on several threads (one candidate per thread drops the least work
    // there). With SSE2 a red-black constraint has no chain for lanes to hide: one candidate per
    // thread, so one thread evaluates one candidate at a time and does not speculate.
    for (int lambda : {1, 2}) {
      SearchOptions rb = test::small_search_options(lambda);
      rb.droplet.constraint_order = ConstraintOrder::red_black;
      for (int threads : {1, 2, 16}) {
        SCOPED_TRACE("red-black, lambda " + std::to_string(lambda) + ", " + std::to_string(threads) + " threads");
        DriveOptions r;
        r.generations = 1;
        r.threads = threads;
        Search one(rb, test::small_search_start(rb), 0);
        const SearchSummary sum = drive(one, r, nullptr);
        const bool blocks =
            width == VectorWidth::avx512 || (width == VectorWidth::avx && (lambda >= 2 || threads == 1));
        if (blocks) {
          EXPECT_EQ(sum.speculation.threads, threads);
          EXPECT_EQ(sum.speculation.lanes, threads == 16 ? 1 : 8);
        } else {
          EXPECT_EQ(sum.speculation.threads, threads > 1 ? threads : 0);
          EXPECT_EQ(sum.speculation.lanes, threads > 1 ? 1 : 0);
        }
      }
    }
  }
  const SearchOptions o = test::small_search_options(2);
  DriveOptions d;
  d.generations = 1;
  d.threads = 2;
  d.lanes = 3;  // as given
  Search s(o, test::small_search_start(o), 0);
  EXPECT_EQ(drive(s, d, nullptr).speculation.lanes, 3);
  d.speculate = false;
  Search plain(o, test::small_search_start(o), 0);
  const SearchSummary none = drive(plain, d, nullptr);
  EXPECT_EQ(none.speculation.threads, 0);
  EXPECT_EQ(none.speculation.lanes, 0);
  if (lacked.any()) GTEST_SKIP() << lacked.message();
}

TEST(Search, DriveRefusesLanesOutOfRangeByName) {
  const SearchOptions o = test::small_search_options();
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search s(o, best, 0);
  for (int lanes : {-1, 65}) {
    DriveOptions d;
    d.generations = 1;
    d.lanes = lanes;
    try {
      drive(s, d, nullptr);
      ADD_FAILURE() << "lanes = " << lanes << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "lanes = " + std::to_string(lanes) + ": must be in [0, 64]");
    }
  }
  EXPECT_EQ(s.last_generation(), 0) << "nothing ran";
}

TEST(Search, ResumingFromTheStoredBestContinuesTheSameHistory) {
  const SearchOptions o = test::small_search_options();
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search straight(o, best, 0);
  for (int i = 0; i < 12; ++i) straight.next(1);
  Search first(o, best, 0);
  for (int i = 0; i < 5; ++i) first.next(1);
  Search resumed(o, first.best(), first.last_generation());  // what --resume rebuilds
  for (int i = 0; i < 7; ++i) resumed.next(1);
  EXPECT_EQ(resumed.best().medium, straight.best().medium);
  EXPECT_EQ(resumed.best().eval.tortuosity, straight.best().eval.tortuosity);
  EXPECT_EQ(resumed.best().generation, straight.best().generation);
}

TEST(Search, DriveStopsAtGenerationsStopFlagAndCallback) {
  const SearchOptions o = test::small_search_options();
  Configuration best;
  initial_generation(test::small_search_medium(), o, &best);
  Search s(o, best, 0);
  DriveOptions d;
  d.generations = 3;
  int calls = 0;
  SearchSummary sum = drive(s, d, [&](const Generation&, const Configuration&) { return ++calls > 0; });
  EXPECT_EQ(sum.termination, Termination::generations);
  EXPECT_EQ(sum.generations_run, 3);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(sum.evaluations, 3);
  std::atomic<bool> stop{true};
  d.generations = 10;
  d.stop = &stop;
  sum = drive(s, d, {});
  EXPECT_EQ(sum.termination, Termination::interrupted);
  EXPECT_EQ(sum.generations_run, 0);
  d.stop = nullptr;
  sum = drive(s, d, [](const Generation&, const Configuration&) { return false; });
  EXPECT_EQ(sum.termination, Termination::callback);
  EXPECT_EQ(sum.last_generation, 4);
}

TEST(Search, RefusesAStartTheDropletCannotPassOrThatBreaksTheRule) {
  const SearchOptions o = test::small_search_options();
  Configuration best;
  // A wall of touching grains across a walled box: nothing passes, and the rule is broken.
  Medium wall{100, 100, false, {}, nullptr};
  for (int i = 0; i < 5; ++i) wall.grains.push_back({10.0 + 20 * i, 50, 10});
  EXPECT_THROW(initial_generation(wall, o, &best), std::invalid_argument);
  // Spaced grains, but the gaps (2.6) are far narrower than the droplet: it gets stuck.
  Medium sieve{104, 100, false, {}, nullptr};
  for (int i = 0; i < 4; ++i) sieve.grains.push_back({14.0 + 25.3 * i, 50, 11.3});
  ASSERT_FALSE(find_spacing_violation(sieve, o.gap).has_value());
  try {
    initial_generation(sieve, o, &best);
    FAIL() << "expected the droplet to be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("does not pass"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace softdrop
