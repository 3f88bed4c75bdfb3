// Many droplets through many random media: the simulator must never crash, hang or produce
// nonsense, whatever the medium throws at it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

// The defaults through both kinds of media at every porosity the paper measured: none diverges
// (10 080 more, outside the suite: results/calibration/defaults.sh).
TEST(Robustness, ThousandDropletsThroughBothKindsOfMedia) {
  DropletParams p;
  RunOptions o;
  o.stuck_window = 0.2;  // a shorter stuck test keeps the suite quick; stuck is a valid end
  o.check_interval = 8;
  int total = 0, passed = 0;
  for (const MediumKind kind : {MediumKind::overlapping, MediumKind::non_overlapping}) {
    for (const double phi : {0.5, 0.6, 0.7, 0.8, 0.9, 0.95}) {
      for (int medium_index = 0; medium_index < 2; ++medium_index) {
        MediumOptions mo;
        mo.kind = kind;
        mo.porosity = phi;
        mo.seed = 100 + static_cast<std::uint64_t>(medium_index);
        const Medium m = generate_medium(mo);
        BatchOptions b;
        b.droplets = 42;
        b.seed = 7 + static_cast<std::uint64_t>(medium_index);
        const auto runs = run_batch(p, m, o, b);
        for (const RunSummary& r : runs) {
          ++total;
          SCOPED_TRACE(std::string(to_string(kind)) + " phi " + std::to_string(phi) + " medium " +
                       std::to_string(medium_index) + " start " + std::to_string(r.start_x) + ": " + r.reason);
          EXPECT_NE(r.outcome, Outcome::diverged);
          EXPECT_NE(r.outcome, Outcome::timeout);
          EXPECT_TRUE(std::isfinite(r.path_length));
          EXPECT_GT(r.min_area_ratio, 0.3);
          EXPECT_FALSE(r.grain_inside_ring);
          EXPECT_LE(r.max_penetration, p.max_depth + 1e-9);
          if (r.outcome == Outcome::passed) {
            ++passed;
            EXPECT_GE(r.tortuosity, 1.0 - 1e-9);  // a droplet that touches nothing: 1 to rounding
            EXPECT_TRUE(std::isfinite(r.tortuosity));
          }
        }
      }
    }
  }
  EXPECT_EQ(total, 1008);
  EXPECT_GT(passed, 500);  // a physics regression that blocks everything would show here
  std::printf("passed %d of %d droplets\n", passed, total);
}

}  // namespace
}  // namespace softdrop

namespace softdrop {
namespace {

// The red-black constraint order gives other numbers (other rounding) but the same physics: the
// same droplets pass, with the same mean tortuosity within the standard errors, and none diverges.
TEST(Robustness, RedBlackOrderGivesTheSameStatistics) {
  RunOptions o;
  o.stuck_window = 0.2;
  BatchOptions b;
  b.droplets = 60;
  b.seed = 11;
  for (const double phi : {0.85, 0.95}) {
    MediumOptions mo;
    mo.porosity = phi;
    mo.seed = 21;
    const Medium m = generate_medium(mo);
    DropletParams seq, rb;
    rb.constraint_order = ConstraintOrder::red_black;
    const BatchStats a = summarize(run_batch(seq, m, o, b)), c = summarize(run_batch(rb, m, o, b));
    SCOPED_TRACE("phi " + std::to_string(phi));
    EXPECT_EQ(c.diverged, 0);
    EXPECT_EQ(c.timeout, 0);
    EXPECT_NEAR(c.passed, a.passed, 0.1 * b.droplets);
    ASSERT_GT(a.passed, 10);
    EXPECT_LT(std::abs(c.mean_tortuosity - a.mean_tortuosity), 3 * std::hypot(a.standard_error, c.standard_error));
  }
}

}  // namespace
}  // namespace softdrop

namespace softdrop {
namespace {

// Hard cases on the defaults, checked every step: the ring must stay whole (no self-intersection,
// no inversion, no grain inside it) and no mass may sit deeper in a grain than the contact limit.
RunSummary run_checked(const Medium& medium, double x0, double* cx = nullptr, double* cy = nullptr) {
  const DropletParams p;
  RunOptions o;
  o.check_interval = 1;
  Simulation sim(p, medium);
  const RunSummary r = sim.run(x0, o);
  if (cx && cy) sim.centre_of_mass(cx, cy);  // where the run ended
  EXPECT_NE(r.outcome, Outcome::diverged) << r.reason;
  EXPECT_NE(r.outcome, Outcome::timeout) << r.reason;
  EXPECT_FALSE(r.grain_inside_ring);
  EXPECT_GT(r.min_area_ratio, 0.0);
  EXPECT_LE(r.max_penetration, p.max_depth + 1e-9);
  return r;
}

TEST(HardCases, AFallThroughA2000HighBoxOntoOneGrain) {
  // About 1 length unit a step at impact, half an edge: the ring is flattened when it lands on the
  // grain's top, and must come back whole. (The balloon, with its breathing damped, folds into
  // itself in most of these falls; results/calibration/README.md has the numbers.)
  for (const double r : {8.0, 16.0}) {
    const Medium tall{500, 2000, true, {{250, 30, r}}, nullptr};
    for (const double dx : {0.0, 0.5, 2.0, 6.0, 12.0}) {
      SCOPED_TRACE("grain radius " + std::to_string(r) + ", start " + std::to_string(dx) + " off its axis");
      const RunSummary run = run_checked(tall, 250 + dx);
      EXPECT_EQ(run.outcome, Outcome::passed) << run.reason;
      EXPECT_EQ(run.touched, (std::vector<std::int32_t>{0}));
    }
  }
}

TEST(HardCases, AGrainWhereTheRingStarts) {
  // Grains at and across the top of the box, right under the start: the droplet starts clear of
  // the highest one and falls onto it at once. Each run is checked every step (run_checked).
  const DropletParams p;
  for (const Grain g : {Grain{100, 200, 12}, Grain{100, 195, 16}, Grain{103, 188, 8}}) {
    SCOPED_TRACE("grain at y = " + std::to_string(g.y) + ", r = " + std::to_string(g.r));
    const Medium m{200, 200, true, {g}, nullptr};
    Simulation sim(p, m);
    EXPECT_GE(sim.start_height() - p.radius, g.y + g.r);
    // 1e-9 off the grain's axis: the droplet rolls off the grain's top and passes.
    const RunSummary run = run_checked(m, 100 + 1e-9);
    EXPECT_EQ(run.outcome, Outcome::passed) << run.reason;
    EXPECT_EQ(run.touched, (std::vector<std::int32_t>{0}));
  }
  // Two grains of radius 12 touching side by side, right under the start: the droplet lands in
  // the notch between them, a stable rest whatever the rounding, and the rest test ends it there,
  // whole and on the axis of the notch.
  const Grain left{88, 195, 12}, right{112, 195, 12};
  double cx = 0, cy = 0;
  const RunSummary balanced = run_checked(Medium{200, 200, true, {left, right}, nullptr}, 100, &cx, &cy);
  EXPECT_EQ(balanced.outcome, Outcome::stuck) << balanced.reason;
  EXPECT_EQ(balanced.reason.rfind("at rest", 0), 0u) << balanced.reason;
  EXPECT_NEAR(cx, 100, 0.01);
  EXPECT_GT(cy, left.y);
  EXPECT_EQ(balanced.touched, (std::vector<std::int32_t>{0, 1}));
  EXPECT_GT(balanced.min_area_ratio, 0.95);  // (run_checked checks that no grain is inside it)
}

TEST(HardCases, TheNarrowestPoreItPasses) {
  // Two grains of radius 16 side by side: the droplet (16 across) squeezes through a gap of 12,
  // and rests on a gap of 11. Its internal viscosity keeps its shape stiff, so it squeezes less
  // than the balloon did (a gap of 7).
  auto pore = [](double gap) {
    return Medium{200, 200, true, {{100 - gap / 2 - 16, 120, 16}, {100 + gap / 2 + 16, 120, 16}}, nullptr};
  };
  const RunSummary through = run_checked(pore(12), 100);
  EXPECT_EQ(through.outcome, Outcome::passed) << through.reason;
  EXPECT_LT(through.min_area_ratio, 0.9) << "it squeezes";
  const RunSummary held = run_checked(pore(11), 100);
  EXPECT_EQ(held.outcome, Outcome::stuck) << held.reason;
}

}  // namespace
}  // namespace softdrop
