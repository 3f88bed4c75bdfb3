// A sweep's per-porosity points: droplets pooled over a porosity's media, and the two standard
// errors of their mean <T> (over droplets; over media as clusters), to exact expected values.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "softdrop/sweep.hpp"

namespace softdrop {
namespace {

// A medium of porosity 0.6 whose droplets passed with these T, and `stuck` more that did not.
SweepMedium medium(const std::vector<double>& passed, int stuck) {
  SweepMedium m;
  m.target_porosity = 0.6, m.porosity = 0.6;
  for (double t : passed) m.droplets.push_back({0, 0, Outcome::passed, t, 1});
  for (int i = 0; i < stuck; ++i) m.droplets.push_back({0, 0, Outcome::stuck, 0, 1});
  return m;
}

TEST(Sweep, PointsPoolTheDropletsOfAPorosity) {
  SweepMedium m1, m2, m3;
  m1.target_porosity = m2.target_porosity = 0.8;
  m3.target_porosity = 0.9;
  m1.porosity = 0.79, m2.porosity = 0.81, m3.porosity = 0.9;
  m1.droplets = {{0, 0, Outcome::passed, 1.2, 1}, {1, 0, Outcome::stuck, 0, 1}};
  m2.droplets = {{0, 0, Outcome::passed, 1.4, 1}, {1, 0, Outcome::passed, 1.3, 1}};
  m3.droplets = {{0, 0, Outcome::passed, 1.1, 1}};
  const auto p = sweep_points({m3, m1, m2});
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].target_porosity, 0.8);
  EXPECT_DOUBLE_EQ(p[0].porosity, 0.8);
  EXPECT_EQ(p[0].droplets, 4);
  EXPECT_EQ(p[0].passed, 3);
  EXPECT_DOUBLE_EQ(p[0].mean_t, 1.3);
  EXPECT_NEAR(p[0].standard_error, 0.1 / std::sqrt(3.0), 1e-12);
  EXPECT_DOUBLE_EQ(p[0].stuck_fraction, 0.25);
  EXPECT_EQ(p[1].passed, 1);
  EXPECT_EQ(p[1].standard_error, 0);
}

// The media's standard error treats each medium as a cluster of correlated droplets: here three
// media pass 2, 1 and 3 droplets (T summing to 2.2, 1.5 and 3.6, mean 7.3 / 6), so
// var = 3/2 * ((2.2 - 2 m)^2 + (1.5 - m)^2 + (3.6 - 3 m)^2) / 6^2 with m = 7.3 / 6.
TEST(Sweep, PointsGiveTheStandardErrorOverMediaAsClusters) {
  const auto p = sweep_points({medium({1.0, 1.2}, 1), medium({1.5}, 0), medium({}, 3), medium({1.1, 1.3, 1.2}, 0)});
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].media, 4);
  EXPECT_EQ(p[0].media_passed, 3);  // the medium where none passed is no cluster
  const double m = 7.3 / 6;
  const double r1 = 2.2 - 2 * m, r2 = 1.5 - m, r3 = 3.6 - 3 * m;
  EXPECT_NEAR(p[0].media_standard_error, std::sqrt(1.5 * (r1 * r1 + r2 * r2 + r3 * r3)) / 6, 1e-15);
  EXPECT_NEAR(p[0].media_standard_error, 0.0756148, 1e-7);
  // These droplets vary more between media than within them: the media's error is the larger.
  EXPECT_GT(p[0].media_standard_error, p[0].standard_error);

  // With one passed droplet in each medium the clusters are the droplets, and the two errors agree.
  const auto q = sweep_points({medium({1.2}, 4), medium({1.45}, 0), medium({1.31}, 2), medium({1.05}, 1)});
  EXPECT_EQ(q[0].media_passed, 4);
  EXPECT_NEAR(q[0].media_standard_error, q[0].standard_error, 1e-15);
  EXPECT_GT(q[0].standard_error, 0);

  // Fewer than two media with a passed droplet: no error, however many droplets passed.
  const auto one = sweep_points({medium({1.2, 1.4, 1.3}, 0), medium({}, 5)});
  EXPECT_EQ(one[0].media_passed, 1);
  EXPECT_EQ(one[0].media_standard_error, 0);
  EXPECT_GT(one[0].standard_error, 0);
}

// Per medium first: the media's own means 1.1, 1.5 and 1.2 (the medium where none passed has
// none), their plain mean 3.8 / 3 and its error sd / sqrt(3). The pooled mean 7.3 / 6 weighs the
// three-droplet medium three times; this one counts each medium once.
TEST(Sweep, PointsAverageEachMediumFirstAsWell) {
  const auto p = sweep_points({medium({1.0, 1.2}, 1), medium({1.5}, 0), medium({}, 3), medium({1.1, 1.3, 1.2}, 0)});
  ASSERT_EQ(p.size(), 1u);
  const double mean = 3.8 / 3;
  EXPECT_NEAR(p[0].per_medium_t, mean, 1e-15);
  const double ss = (1.1 - mean) * (1.1 - mean) + (1.5 - mean) * (1.5 - mean) + (1.2 - mean) * (1.2 - mean);
  EXPECT_NEAR(p[0].per_medium_standard_error, std::sqrt(ss / 2 / 3), 1e-15);
  EXPECT_NEAR(p[0].per_medium_standard_error, 0.1201850, 1e-7);
  EXPECT_NE(p[0].per_medium_t, p[0].mean_t);

  // With as many droplets passed in every medium the two averagings are the same mean.
  const auto even = sweep_points({medium({1.0, 1.4}, 0), medium({1.3, 1.5}, 2)});
  EXPECT_NEAR(even[0].per_medium_t, even[0].mean_t, 1e-15);

  // One medium with a passed droplet: its mean, and no error.
  const auto one = sweep_points({medium({1.2, 1.4}, 0), medium({}, 5)});
  EXPECT_NEAR(one[0].per_medium_t, 1.3, 1e-15);
  EXPECT_EQ(one[0].per_medium_standard_error, 0);
  // None passed: 0, as mean_t.
  EXPECT_EQ(sweep_points({medium({}, 2)})[0].per_medium_t, 0);
}

}  // namespace
}  // namespace softdrop
