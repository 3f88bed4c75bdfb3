// Many droplets through many random media: the simulator must never crash, hang or produce
// nonsense, whatever the medium throws at it.
#include <gtest/gtest.h>

#include <cmath>

#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"

namespace softdrop {
namespace {

TEST(Robustness, ThousandDropletsThroughOverlappingMedia) {
  DropletParams p;
  RunOptions o;
  o.stuck_window = 0.2;  // a shorter stuck test keeps the suite quick; stuck is a valid end
  o.max_steps = 400000;
  o.check_interval = 8;
  int total = 0, passed = 0;
  for (const double phi : {0.5, 0.6, 0.7, 0.8, 0.9}) {
    for (int medium_index = 0; medium_index < 4; ++medium_index) {
      MediumOptions mo;
      mo.porosity = phi;
      mo.seed = 100 + static_cast<std::uint64_t>(medium_index);
      const Medium m = generate_medium(mo);
      BatchOptions b;
      b.droplets = 50;
      b.seed = 7 + static_cast<std::uint64_t>(medium_index);
      const auto runs = run_batch(p, m, o, b);
      for (const RunSummary& r : runs) {
        ++total;
        SCOPED_TRACE("phi " + std::to_string(phi) + " medium " + std::to_string(medium_index) +
                     " start " + std::to_string(r.start_x) + ": " + r.reason);
        EXPECT_TRUE(r.outcome == Outcome::passed || r.outcome == Outcome::stuck ||
                    r.outcome == Outcome::timeout || r.outcome == Outcome::diverged);
        EXPECT_NE(r.outcome, Outcome::diverged);
        EXPECT_NE(r.outcome, Outcome::timeout);
        EXPECT_TRUE(std::isfinite(r.path_length));
        EXPECT_GT(r.min_area_ratio, 0.3);
        EXPECT_FALSE(r.grain_inside_ring);
        EXPECT_LE(r.max_penetration, 0.25 * p.radius);
        if (r.outcome == Outcome::passed) {
          ++passed;
          EXPECT_GE(r.tortuosity, 1.0 - 1e-9);  // a droplet that touches nothing: 1 to rounding
          EXPECT_TRUE(std::isfinite(r.tortuosity));
        }
      }
    }
  }
  EXPECT_EQ(total, 1000);
  EXPECT_GT(passed, 100);  // a physics regression that blocks everything would show here
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
    EXPECT_LT(std::abs(c.mean_tortuosity - a.mean_tortuosity),
              3 * std::hypot(a.standard_error, c.standard_error));
  }
}

}  // namespace
}  // namespace softdrop
