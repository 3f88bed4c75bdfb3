// The paper's two averagings of per-medium points: the groups sorted by T or by phi, to exact
// expected values, and the points left over after the last full group dropped or kept.
#include "studies/averaging.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace softdrop {
namespace {

const std::vector<MediumPoint> kPoints{{0.5, 1.4}, {0.9, 1.0}, {0.6, 1.1}, {0.7, 1.3}, {0.8, 1.2}};

TEST(Averaging, GroupsSortedByTOrByPhi) {
  const auto by_t = group_averages(kPoints, AveragingType::by_t, 2);
  ASSERT_EQ(by_t.size(), 2u);  // the fifth point is left over
  EXPECT_DOUBLE_EQ(by_t[0].t, 1.05);
  EXPECT_DOUBLE_EQ(by_t[0].phi, 0.75);
  EXPECT_DOUBLE_EQ(by_t[1].t, 1.25);
  EXPECT_DOUBLE_EQ(by_t[1].phi, 0.75);
  const auto by_phi = group_averages(kPoints, AveragingType::by_phi, 2);
  EXPECT_DOUBLE_EQ(by_phi[0].phi, 0.55);
  EXPECT_DOUBLE_EQ(by_phi[0].t, 1.25);
  EXPECT_NEAR(by_phi[0].t_se, 0.15, 1e-12);  // sd 0.15 sqrt(2) over sqrt(2) points
  EXPECT_THROW(group_averages(kPoints, AveragingType::by_t, 0), std::invalid_argument);
}

TEST(Averaging, TheLeftoverIsTheHighEndAndIsKeptAsASmallerLastGroupWhenAsked) {
  // Groups of 3 from 5 points: one full group and two left over, the highest in T (1.3 and 1.4 at
  // phi 0.7 and 0.5) or in phi (0.8 and 0.9 at T 1.2 and 1.0).
  const auto dropped = group_averages(kPoints, AveragingType::by_t, 3, Leftover::drop);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].count, 3);
  const auto by_t = group_averages(kPoints, AveragingType::by_t, 3, Leftover::keep);
  ASSERT_EQ(by_t.size(), 2u);
  EXPECT_EQ(by_t[0].count, 3);
  EXPECT_EQ(by_t[0].t, dropped[0].t);  // the full groups are the same to the bit
  EXPECT_EQ(by_t[0].t_se, dropped[0].t_se);
  EXPECT_EQ(by_t[1].count, 2);
  EXPECT_DOUBLE_EQ(by_t[1].t, 1.35);
  EXPECT_DOUBLE_EQ(by_t[1].phi, 0.6);
  EXPECT_NEAR(by_t[1].t_se, 0.05, 1e-12);
  const auto by_phi = group_averages(kPoints, AveragingType::by_phi, 3, Leftover::keep);
  ASSERT_EQ(by_phi.size(), 2u);
  EXPECT_EQ(by_phi[1].count, 2);
  EXPECT_DOUBLE_EQ(by_phi[1].phi, 0.85);
  EXPECT_DOUBLE_EQ(by_phi[1].t, 1.1);
  // A leftover of one point is a group of one, with no spread to give an error.
  const auto ones = group_averages(kPoints, AveragingType::by_phi, 4, Leftover::keep);
  ASSERT_EQ(ones.size(), 2u);
  EXPECT_EQ(ones[1].count, 1);
  EXPECT_EQ(ones[1].phi, 0.9);
  EXPECT_EQ(ones[1].t, 1.0);
  EXPECT_EQ(ones[1].t_se, 0);
  // Nothing left over: keeping changes nothing.
  const auto whole = group_averages(kPoints, AveragingType::by_t, 5, Leftover::keep);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].count, 5);
}

}  // namespace
}  // namespace softdrop
