// Pairs of droplets in every layout of the step: a pair's two rings as lanes of a lane-by-lane
// block, with the ring-ring stages between those lanes, give each ring the bits of the pair's own
// step (TwoDropletRun::step, a ring group of the two), step by step; and run_pairs_interleaved,
// which steps several pairs as a block or as a ring group, gives every pair run_two_droplets'
// summary, at every vector width.
#include "sim/pair_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixtures.hpp"
#include "same_summary.hpp"
#include "sim/lane_block_step.hpp"
#include "sim/lane_policy.hpp"
#include "sim/two_droplet_run.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

using test::close_behind;
using test::long_enough;

TEST(PairLanes, APairAsTwoLanesOfABlockStepsAsItsOwnStepToTheBit) {
  // Pair `alone` steps itself (a ring group of its two rings). The same pair, beside another (a block of four lanes,
  // at least fewest_block_droplets()), steps as lanes; before the second's release the block has
  // the first rings and a third droplet alone, so there are always enough. Both rings' states and
  // what the ring limit moved agree at every step.
  const Medium medium = test::small_medium_079();
  const DropletParams p;
  const RunOptions o = long_enough();
  test::LackedWidths lacked;
  for (VectorWidth width : {VectorWidth::avx, VectorWidth::avx512}) {
    const test::VectorWidthLimit limit(width);
    if (!lacked.has(limit, width)) continue;
    SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(width)));
    TwoDropletRun alone(p, medium, 100, o, close_behind()), laned(p, medium, 100, o, close_behind()),
        beside(p, medium, 150, o, close_behind());
    Simulation third(p, medium);
    third.place_above(40);
    std::int64_t k = 0, both = 0, contact = 0, limited = 0;
    while (!alone.finished()) {
      alone.step();
      ASSERT_FALSE(laned.finished()) << "step " << k;
      std::vector<Simulation*> rings;
      std::vector<RingPair> pairs;
      std::vector<TwoDropletRun*> runs{&laned};
      if (!beside.finished()) runs.push_back(&beside);
      std::vector<int> pair_of;  // each run's entry of pairs; -1: it steps one ring
      for (TwoDropletRun* run : runs) {
        Simulation *a = nullptr, *b = nullptr;
        run->begin_step(&a, &b);
        pair_of.push_back(a && b ? static_cast<int>(pairs.size()) : -1);
        if (a && b)
          pairs.push_back({static_cast<int>(rings.size()), static_cast<int>(rings.size()) + 1, run->scratch(), 0});
        for (Simulation* sim : {a, b})
          if (sim) rings.push_back(sim);
      }
      rings.push_back(&third);
      LaneBlockStep::step(rings.data(), static_cast<int>(rings.size()), pairs.data(), static_cast<int>(pairs.size()));
      for (std::size_t r = 0; r < runs.size(); ++r)
        runs[r]->end_step(pair_of[r] < 0 ? 0 : pairs[static_cast<std::size_t>(pair_of[r])].moved);
      ++k;
      ASSERT_EQ(laned.limited(), alone.limited()) << "step " << k;
      ASSERT_EQ(laned.first().state_hash(), alone.first().state_hash()) << "first ring, step " << k;
      ASSERT_EQ(laned.second().state_hash(), alone.second().state_hash()) << "second ring, step " << k;
      if (pair_of[0] >= 0) {
        ++both;
        contact += laned.scratch()->contacts > 0;
        limited += laned.limited() > 0;
      }
    }
    EXPECT_TRUE(laned.finished());
    // The pair met: the ring-ring stages were at work in the block.
    EXPECT_GT(both, 1000);
    EXPECT_GT(contact, 100);
    EXPECT_GT(limited, 0);
  }
  if (lacked.any()) GTEST_SKIP() << lacked.message();
}

// The summaries the same pairs get from run_pairs_interleaved in `lanes` lanes, by id.
std::map<std::int64_t, TwoDropletSummary> interleaved(int lanes, const std::vector<double>& starts,
                                                      const Medium& medium, const SecondDroplet& second) {
  std::map<std::int64_t, TwoDropletSummary> out;
  std::size_t handed = 0;
  run_pairs_interleaved(
      lanes, DropletParams{}, medium, long_enough(), second,
      [&](PairJob* job) {
        if (handed == starts.size()) return false;
        *job = PairJob{starts[handed], static_cast<std::int64_t>(handed)};
        ++handed;
        return true;
      },
      [&](std::int64_t id, TwoDropletSummary&& s) { out.emplace(id, std::move(s)); });
  return out;
}

TEST(PairLanes, PairsSteppedTogetherGetEachPairsOwnSummaryAtEveryWidth) {
  // Fourteen pairs in 2, 7 or 28 lanes: one pair at a time (a ring group), or several whose lane
  // counts change as they release their second droplets and end, a pair starting as two lanes
  // free; in 28 lanes, up to 28 rings, more than a block's 24, go as two blocks.
  const Medium medium = test::small_medium_079();
  const SecondDroplet second = close_behind();
  const std::vector<double> starts{20, 55, 90, 100, 125, 160, 185, 10, 35, 70, 110, 140, 150, 195};
  std::vector<TwoDropletSummary> alone;
  std::int64_t contact = 0;
  for (double x0 : starts) {
    alone.push_back(run_two_droplets(DropletParams{}, medium, x0, long_enough(), second));
    contact += alone.back().contact_steps;
  }
  EXPECT_GT(contact, 200) << "the pairs meet";
  test::LackedWidths lacked;
  for (VectorWidth width : test::kVectorWidths) {
    const test::VectorWidthLimit limit(width);
    if (!lacked.has(limit, width)) continue;
    for (int lanes : {2, 7, 28}) {
      SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(width)) + ", " + std::to_string(lanes) + " lanes");
      const std::map<std::int64_t, TwoDropletSummary> got = interleaved(lanes, starts, medium, second);
      ASSERT_EQ(got.size(), starts.size());
      for (std::size_t i = 0; i < starts.size(); ++i) {
        test::expect_same_pair(got.at(static_cast<std::int64_t>(i)), alone[i], "pair " + std::to_string(i));
      }
    }
  }
  if (lacked.any()) GTEST_SKIP() << lacked.message();
}

TEST(PairLanes, ABadLaneCountIsRefusedNamingIt) {
  const Medium medium = test::small_medium_079();
  for (int lanes : {1, 65}) {
    try {
      interleaved(lanes, {100}, medium, close_behind());
      ADD_FAILURE() << "lanes = " << lanes << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "lanes = " + std::to_string(lanes) + ": must be in [2, 64]");
    }
  }
}

}  // namespace
}  // namespace softdrop
