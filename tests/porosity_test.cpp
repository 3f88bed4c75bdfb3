#include <gtest/gtest.h>

#include <cmath>

#include "softdrop/medium.hpp"

namespace softdrop {
namespace {

// Area of the circular segment of a disc of radius r cut off beyond distance h from its centre.
double segment(double r, double h) { return r * r * std::acos(h / r) - h * std::sqrt(r * r - h * h); }

TEST(Porosity, SingleDiscInsideTheBox) {
  const Medium m{100, 80, true, {{40, 30, 10}}, nullptr};
  EXPECT_NEAR(solid_area(m), M_PI * 100, 1e-10);
}

TEST(Porosity, DiscAcrossThePeriodicSeamCountsOnce) {
  const Medium m{100, 80, true, {{3, 30, 10}}, nullptr};
  EXPECT_NEAR(solid_area(m), M_PI * 100, 1e-10);
  const Medium walls{100, 80, false, {{3, 30, 10}}, nullptr};  // without periodicity the part x < 0 is cut
  EXPECT_NEAR(solid_area(walls), M_PI * 100 - segment(10, 3), 1e-10);
}

TEST(Porosity, DiscCutByTopAndBottom) {
  const Medium m{100, 80, true, {{50, 76, 10}, {20, -5, 10}}, nullptr};
  EXPECT_NEAR(solid_area(m), (M_PI * 100 - segment(10, 4)) + segment(10, 5), 1e-10);
}

TEST(Porosity, TwoOverlappingDiscsLens) {
  const double r = 10, d = 12;
  const Medium m{100, 80, true, {{40, 40, r}, {40 + d, 40, r}}, nullptr};
  const double lens = 2 * segment(r, d / 2);
  EXPECT_NEAR(solid_area(m), 2 * M_PI * r * r - lens, 1e-10);
}

TEST(Porosity, DiscInsideAnotherAndDuplicates) {
  const Medium m{100, 80, true, {{40, 40, 10}, {42, 40, 3}, {40, 40, 10}}, nullptr};
  EXPECT_NEAR(solid_area(m), M_PI * 100, 1e-10);
}

TEST(Porosity, DiscCoveringTheWholeBox) {
  const Medium m{10, 10, false, {{5, 5, 20}}, nullptr};
  EXPECT_NEAR(exact_porosity(m), 0.0, 1e-12);
}

TEST(Porosity, ExactAgreesWithMonteCarloOnRandomMedia) {
  struct Case {
    MediumKind kind;
    double porosity;
    bool periodic;
  };
  for (const Case c : {Case{MediumKind::overlapping, 0.5, true}, Case{MediumKind::overlapping, 0.8, true},
                       Case{MediumKind::overlapping, 0.6, false}, Case{MediumKind::non_overlapping, 0.75, true}}) {
    MediumOptions o;
    o.kind = c.kind;
    o.porosity = c.porosity;
    o.periodic = c.periodic;
    o.seed = 42;
    const Medium m = generate_medium(o);
    const double exact = exact_porosity(m);
    const PorosityEstimate mc = monte_carlo_porosity(m, 1'000'000, 99);
    EXPECT_LT(std::abs(exact - mc.porosity), 3 * mc.standard_error)
        << "phi " << c.porosity << ": exact " << exact << " mc " << mc.porosity << " +- " << mc.standard_error;
  }
}

}  // namespace
}  // namespace softdrop
