// Relaxed media: non-overlapping grains placed at random and pushed apart until the spacing rule
// holds. They reach porosities and gaps at which random sequential addition jams.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "media/spacing.hpp"
#include "softdrop/medium.hpp"

namespace softdrop {
namespace {

MediumOptions relaxed(double porosity, double gap, bool periodic = true) {
  MediumOptions o;
  o.kind = MediumKind::relaxed;
  o.porosity = porosity;
  o.gap = gap;
  o.periodic = periodic;
  return o;
}

double disc_area(const Medium& m) {
  double discs = 0;
  for (const Grain& g : m.grains) discs += M_PI * g.r * g.r;
  return discs;
}

// Every pair by brute force, periodic in x or not, without the triangulation.
void expect_rule_holds(const Medium& m, double gap) {
  EXPECT_FALSE(find_spacing_violation(m, gap).has_value());
  for (std::size_t i = 0; i < m.grains.size(); ++i) {
    const Grain& a = m.grains[i];
    ASSERT_GE(a.y - a.r, 0) << i;
    ASSERT_LE(a.y + a.r, m.height) << i;
    if (!m.periodic) {
      ASSERT_GE(a.x - a.r, 0) << i;
      ASSERT_LE(a.x + a.r, m.width) << i;
    }
    for (std::size_t j = i + 1; j < m.grains.size(); ++j) {
      const Grain& b = m.grains[j];
      double dx = std::abs(a.x - b.x);
      if (m.periodic) dx = std::min(dx, m.width - dx);
      ASSERT_GE(std::hypot(dx, a.y - b.y), required_distance(a.r, b.r, gap)) << i << ' ' << j;
    }
  }
}

TEST(RelaxedMedium, KeepsWideGapsAtAPorosityWhereSequentialAdditionJams) {
  for (const bool periodic : {true, false}) {
    SCOPED_TRACE(periodic ? "periodic" : "walls");
    MediumOptions sequential = relaxed(0.5, 0.4, periodic);
    sequential.kind = MediumKind::non_overlapping;
    sequential.max_failed_attempts = 20000;
    EXPECT_THROW(generate_medium(sequential), std::runtime_error);

    const MediumOptions o = relaxed(0.5, 0.4, periodic);
    const Medium m = generate_medium(o);
    expect_rule_holds(m, o.gap);
    // Disjoint discs inside the box: the porosity is one minus their area over the box's (to the
    // exact area's rounding at grains that touch a wall), and the grain count is the one nearest
    // the target, within half the largest grain's share of the box.
    const double box = o.width * o.height;
    EXPECT_NEAR(exact_porosity(m), 1 - disc_area(m) / box, 1e-9);
    EXPECT_LE(std::abs(exact_porosity(m) - 0.5), 0.5 * M_PI * o.r_max * o.r_max / box);
    EXPECT_GT(m.grains.size(), 30u);  // (about 36 of radii 16 to 48 in 500 x 500)
  }
}

TEST(RelaxedMedium, AGrainCountIsRelaxedToo) {
  MediumOptions o = relaxed(0.5, 0.3);
  o.grains = 100, o.width = 300, o.height = 300, o.r_min = 8, o.r_max = 16;
  const Medium m = generate_medium(o);
  EXPECT_EQ(m.grains.size(), 100u);
  expect_rule_holds(m, o.gap);
}

TEST(RelaxedMedium, SameSeedSameMediumOtherSeedOtherMedium) {
  MediumOptions o = relaxed(0.55, 0.3);
  const Medium a = generate_medium(o), b = generate_medium(o);
  EXPECT_EQ(a, b);  // bit for bit
  o.seed = 2;
  EXPECT_NE(generate_medium(o), a);
}

TEST(RelaxedMedium, TooManyGrainsForTheGapIsAClearError) {
  try {
    generate_medium(relaxed(0.5, 0.6));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("porosity = 0.5: unreachable for relaxed grains with gap 0.6", 0), 0u) << what;
  }
  EXPECT_EQ(parse_medium_kind("relaxed"), MediumKind::relaxed);
  EXPECT_STREQ(to_string(MediumKind::relaxed), "relaxed");
}

}  // namespace
}  // namespace softdrop
