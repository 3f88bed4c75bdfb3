#include "softdrop/medium.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "media/spacing.hpp"

namespace softdrop {
namespace {

// Brute force check of the spacing rule, periodic in x, independent of CGAL.
bool pair_violates(const Grain& a, const Grain& b, double width, bool periodic, double gap) {
  double dx = std::abs(a.x - b.x);
  if (periodic) dx = std::min(dx, width - dx);
  const double dy = a.y - b.y, need = required_distance(a.r, b.r, gap);
  return dx * dx + dy * dy < need * need;
}

TEST(Medium, OverlappingStopsAtTheFirstGrainThatReachesTheTarget) {
  MediumOptions o;
  o.porosity = 0.7;
  o.seed = 5;
  const Medium m = generate_medium(o);
  const double phi = exact_porosity(m);
  EXPECT_LE(phi, 0.7);
  Medium one_less = m;
  one_less.grains.pop_back();
  EXPECT_GT(exact_porosity(one_less), 0.7);
  EXPECT_GT(m.grains.size(), 20u);  // (about 28 of radii 16 to 48 in 500 x 500)
  for (const Grain& g : m.grains) {
    EXPECT_GE(g.r, o.r_min);
    EXPECT_LE(g.r, o.r_max);
    EXPECT_GE(g.x, 0);
    EXPECT_LT(g.x, o.width);
  }
}

TEST(Medium, LognormalRadiiStayInRangeAndCentreOnTheMedian) {
  MediumOptions o;
  o.radii = RadiusDistribution::lognormal;
  o.r_min = 4;
  o.r_max = 30;
  o.r_median = 10;
  o.r_sigma = 0.3;
  o.porosity = 0.5;
  const Medium m = generate_medium(o);
  ASSERT_GT(m.grains.size(), 300u);
  std::vector<double> r;
  for (const Grain& g : m.grains) {
    ASSERT_GE(g.r, o.r_min);
    ASSERT_LE(g.r, o.r_max);
    r.push_back(g.r);
  }
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
  EXPECT_NEAR(r[r.size() / 2], 10, 1.0);  // sample median of a few hundred draws
  double mean_log = 0, var_log = 0;
  for (double v : r) mean_log += std::log(v) / static_cast<double>(r.size());
  for (double v : r) var_log += (std::log(v) - mean_log) * (std::log(v) - mean_log) / static_cast<double>(r.size());
  EXPECT_NEAR(std::sqrt(var_log), 0.3, 0.04);
  o.r_median = 40;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("r-median"), std::string::npos);
}

TEST(Medium, SameSeedSameMediumOtherSeedOtherMedium) {
  MediumOptions o;
  EXPECT_EQ(generate_medium(o), generate_medium(o));
  MediumOptions other = o;
  other.seed = 2;
  EXPECT_NE(generate_medium(o).grains, generate_medium(other).grains);
}

TEST(Medium, NonOverlappingKeepsTheGapBetweenEveryPair) {
  for (const bool periodic : {true, false}) {
    MediumOptions o;
    o.kind = MediumKind::non_overlapping;
    o.periodic = periodic;
    o.porosity = 0.7;
    o.seed = 11;
    const Medium m = generate_medium(o);
    EXPECT_LE(exact_porosity(m), 0.7);
    // Non-overlapping grains inside the box: exact porosity is 1 - sum of disc areas / box.
    double discs = 0;
    for (const Grain& g : m.grains) discs += M_PI * g.r * g.r;
    EXPECT_NEAR(exact_porosity(m), 1 - discs / (o.width * o.height), 1e-12);
    EXPECT_FALSE(find_spacing_violation(m, o.gap).has_value());
    for (std::size_t i = 0; i < m.grains.size(); ++i) {
      const Grain& g = m.grains[i];
      ASSERT_GE(g.y - g.r, 0);
      ASSERT_LE(g.y + g.r, o.height);
      if (!periodic) {
        ASSERT_GE(g.x - g.r, 0);
      }
      for (std::size_t j = i + 1; j < m.grains.size(); ++j)
        ASSERT_FALSE(pair_violates(g, m.grains[j], o.width, periodic, o.gap)) << i << ' ' << j;
    }
  }
}

TEST(Medium, SpacingViolationIsFoundAcrossThePeriodicSeam) {
  Medium m{100, 100, true, {{2, 50, 5}, {95, 50, 5}}, nullptr};  // 7 apart through the seam, need 10.65
  const auto v = find_spacing_violation(m, 0.13);
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(*v, std::make_pair(0, 1));
  m.periodic = false;  // now grain 0 sticks out of the box at x < 0
  EXPECT_EQ(find_spacing_violation(m, 0.13), std::make_pair(0, 0));
  m.grains[0].x = 8;
  EXPECT_FALSE(find_spacing_violation(m, 0.13).has_value());
  m.periodic = true;  // 16 apart through the seam: fine
  EXPECT_FALSE(find_spacing_violation(m, 0.13).has_value());
  m.grains[1].y = 3;  // sticks out of the box in y
  EXPECT_EQ(find_spacing_violation(m, 0.13), std::make_pair(1, 1));
}

TEST(Medium, SpacingIndexAnswersLikeBruteForce) {
  SpacingIndex index(100, 100, true, 0.13, 6);
  index.insert({50, 50, 6});
  EXPECT_FALSE(index.can_place({50 + 12 + 0.77, 50, 6}));  // needs 12 + 0.78
  EXPECT_TRUE(index.can_place({50 + 12 + 0.79, 50, 6}));
  index.insert({1, 20, 5});
  EXPECT_FALSE(index.can_place({97, 20, 5}));  // 4 apart through the seam
  EXPECT_FALSE(index.can_place({10, 3, 5}));   // outside the box in y
}

TEST(Medium, UnreachableNonOverlappingTargetIsAClearError) {
  MediumOptions o;
  o.kind = MediumKind::non_overlapping;
  o.porosity = 0.1;
  o.max_failed_attempts = 2000;
  try {
    generate_medium(o);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("porosity"), std::string::npos) << e.what();
  }
}

TEST(Medium, InvalidOptionsNameTheParameter) {
  auto why_of = [](MediumOptions o) {
    std::string why;
    EXPECT_FALSE(o.IsValid(&why));
    return why;
  };
  MediumOptions o;
  o.porosity = 1.0;
  EXPECT_NE(why_of(o).find("porosity"), std::string::npos);
  o = {};
  o.porosity = std::nan("");
  EXPECT_NE(why_of(o).find("porosity"), std::string::npos);
  o = {};
  o.r_min = -1;
  EXPECT_NE(why_of(o).find("r-min"), std::string::npos);
  o = {};
  o.r_max = 1;
  EXPECT_NE(why_of(o).find("r-max"), std::string::npos);
  EXPECT_THROW(generate_medium(o), std::invalid_argument);
  EXPECT_THROW(parse_medium_kind("lattice"), std::invalid_argument);
}

}  // namespace
}  // namespace softdrop
