// The search's moves: the all-grain move keeps the spacing rule, the radii and its step bound; moves
// are deterministic per generation and index; the single move moves one touched grain; a refused
// jump leaves the grain where it was.
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.hpp"
#include "media/spacing.hpp"
#include "search_fixtures.hpp"
#include "softdrop/search.hpp"

namespace softdrop {
namespace {

double periodic_dx(double a, double b, double w) {
  double d = b - a;
  return d - w * std::round(d / w);
}

TEST(Mutation, AllGrainMoveKeepsSpacingRadiiAndStepBound) {
  const SearchOptions o = test::small_search_options();
  const Configuration parent = test::small_search_start(o);
  for (int k = 0; k < 20; ++k) {
    const Candidate c = make_candidate(parent, 1, k, o);
    ASSERT_EQ(c.kind, MoveKind::all);
    ASSERT_EQ(c.medium.grains.size(), parent.medium.grains.size());
    EXPECT_FALSE(find_spacing_violation(c.medium, o.gap).has_value());
    int moved = 0;
    for (std::size_t i = 0; i < c.medium.grains.size(); ++i) {
      const Grain& a = parent.medium.grains[i];
      const Grain& b = c.medium.grains[i];
      EXPECT_EQ(a.r, b.r);
      EXPECT_GE(b.x, 0);
      EXPECT_LT(b.x, c.medium.width);
      const double dx = periodic_dx(a.x, b.x, c.medium.width), dy = b.y - a.y;
      EXPECT_LE(std::hypot(dx, dy), o.step * (1 + 1e-12));
      moved += (a.x != b.x || a.y != b.y);
    }
    EXPECT_EQ(moved, c.moved);
    EXPECT_GT(c.moved, 0);
  }
}

TEST(Mutation, IsDeterministicPerGenerationAndIndex) {
  const SearchOptions o = test::small_search_options();
  const Configuration parent = test::small_search_start(o);
  EXPECT_EQ(make_candidate(parent, 3, 1, o).medium, make_candidate(parent, 3, 1, o).medium);
  EXPECT_NE(make_candidate(parent, 3, 1, o).medium, make_candidate(parent, 3, 2, o).medium);
  EXPECT_NE(make_candidate(parent, 3, 1, o).medium, make_candidate(parent, 4, 1, o).medium);
  SearchOptions other = o;
  other.seed = o.seed + 1;
  EXPECT_NE(make_candidate(parent, 3, 1, o).medium, make_candidate(parent, 3, 1, other).medium);
}

TEST(Mutation, SingleMoveMovesOneTouchedGrain) {
  SearchOptions o = test::small_search_options();
  const Configuration parent = test::small_search_start(o);
  ASSERT_FALSE(parent.eval.touched.empty());
  EXPECT_EQ(move_kind(10, o), MoveKind::single);
  EXPECT_EQ(move_kind(11, o), MoveKind::all);
  for (int k = 0; k < 10; ++k) {
    const Candidate c = make_candidate(parent, 10, k, o);
    ASSERT_EQ(c.kind, MoveKind::single);
    EXPECT_TRUE(std::binary_search(parent.eval.touched.begin(), parent.eval.touched.end(), c.moved_grain));
    int changed = 0;
    for (std::size_t i = 0; i < c.medium.grains.size(); ++i)
      if (!(c.medium.grains[i] == parent.medium.grains[i])) {
        ++changed;
        EXPECT_EQ(static_cast<int>(i), c.moved_grain);
      }
    EXPECT_EQ(changed, c.moved);
    EXPECT_FALSE(find_spacing_violation(c.medium, o.gap).has_value());
  }
  o.single_every = 0;
  EXPECT_EQ(move_kind(10, o), MoveKind::all);
}

TEST(Mutation, RefusedJumpsLeaveTheGrainInPlace) {
  // A grain that exactly fills a walled box: every jump would leave the box, so all are refused.
  SearchOptions o = test::small_search_options();
  Configuration parent;
  parent.medium = Medium{24, 24, false, {{12, 12, 12}}, nullptr};
  const Candidate c = make_candidate(parent, 1, 0, o);
  EXPECT_EQ(c.moved, 0);
  EXPECT_EQ(c.medium, parent.medium);
}

}  // namespace
}  // namespace softdrop
