// The Provot length constraint of the ring's springs: it fixes stretch and compression alike,
// converges in both orders (sequential and red-black), gives exactly the bits of each order written
// out plainly, and leaves a spring whose length rounds to a limit at that limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fixtures.hpp"
#include "softdrop/droplet.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {

using test::spring_length;

TEST(Droplet, ProvotConstraintFixesStretchAndCompressionSymmetrically) {
  DropletState s;
  s.resize(4);
  // A square of side 1 (rest length 1) with one edge stretched and one compressed.
  const double xs[4] = {0, 1.5, 1.5, 0}, ys[4] = {0, 0, 1, 1};
  for (int i = 0; i < 4; ++i) s.x[i] = xs[i], s.y[i] = ys[i];
  s.px = s.x;
  s.py = s.y;
  // Edge 0-1 is 1.5 long: 0.4 beyond the 1.1 limit, so each end moves 0.2 inwards.
  // Edge 1-2 is then 1.0 (fine); edge 2-3 is 1.5 - after the first fix it is 1.5: same fix.
  EXPECT_GT(apply_length_constraint(&s, 1.0, 0.1, 1), 0);
  EXPECT_DOUBLE_EQ(s.x[0], 0.2);
  EXPECT_DOUBLE_EQ(s.x[1], 1.3);
  EXPECT_DOUBLE_EQ(spring_length(s, 0), 1.1);
  // Compression: two points 0.5 apart with rest length 1 and 10 % limit end 0.9 apart, midpoint kept.
  DropletState c;
  c.resize(3);
  c.x = {0, 0.5, 0.25};
  c.y = {0, 0, 0.9};  // after the fix the third point's edges are ~1.006 long: within limits
  apply_length_constraint(&c, 1.0, 0.1, 1);
  EXPECT_DOUBLE_EQ(c.x[0], -0.2);
  EXPECT_DOUBLE_EQ(c.x[1], 0.7);
  EXPECT_DOUBLE_EQ(c.y[0], 0.0);
  // Previous positions are not touched: the implied velocity follows the correction.
  EXPECT_EQ(s.px[0], 0.0);
}

TEST(Droplet, ConstraintPassesConvergeOnARandomRing) {
  DropletParams p;
  DropletState s;
  place_droplet(p, 0, 0, &s);
  Rng rng(3);
  for (int i = 0; i < s.size(); ++i) s.x[i] += rng.uniform(-0.3, 0.3), s.y[i] += rng.uniform(-0.3, 0.3);
  auto worst = [&] {
    double w = 0;
    for (int i = 0; i < s.size(); ++i) {
      const double strain = spring_length(s, i) / p.rest_length() - 1;
      w = std::max(w, std::abs(strain) - p.max_strain);
    }
    return w;
  };
  const double before = worst();
  ASSERT_GT(before, 0.05);
  apply_length_constraint(&s, p.rest_length(), p.max_strain, 1);
  const double one_pass = worst();
  apply_length_constraint(&s, p.rest_length(), p.max_strain, 200);
  // Gauss-Seidel passes converge: each fix disturbs the neighbours a little less.
  EXPECT_LT(one_pass, before);
  EXPECT_LT(worst(), 1e-4);
  EXPECT_LT(worst(), 0.01 * one_pass);
}

TEST(Droplet, RedBlackOrderConvergesToo) {
  // Odd and even rings: the red-black order reaches every spring, including an odd ring's
  // closing one, and its passes converge like the sequential ones.
  for (int masses : {40, 41}) {
    DropletParams p;
    p.masses = masses;
    DropletState s;
    place_droplet(p, 0, 0, &s);
    Rng rng(5);
    for (int i = 0; i < s.size(); ++i) s.x[i] += rng.uniform(-0.3, 0.3), s.y[i] += rng.uniform(-0.3, 0.3);
    auto worst = [&] {
      double w = 0;
      for (int i = 0; i < s.size(); ++i)
        w = std::max(w, std::abs(spring_length(s, i) / p.rest_length() - 1) - p.max_strain);
      return w;
    };
    const double before = worst();
    ASSERT_GT(before, 0.05);
    apply_length_constraint(&s, p.rest_length(), p.max_strain, 200, ConstraintOrder::red_black);
    EXPECT_LT(worst(), 1e-4) << masses << " masses";
  }
  // One half-pass fixes the stretched square's edges 0-1 and 2-3 exactly, as the sequential pass does.
  DropletState s;
  s.resize(4);
  const double xs[4] = {0, 1.5, 1.5, 0}, ys[4] = {0, 0, 1, 1};
  for (int i = 0; i < 4; ++i) s.x[i] = xs[i], s.y[i] = ys[i];
  apply_length_constraint(&s, 1.0, 0.1, 1, ConstraintOrder::red_black);
  EXPECT_DOUBLE_EQ(spring_length(s, 0), 1.1);
  EXPECT_DOUBLE_EQ(spring_length(s, 2), 1.1);
  EXPECT_EQ(parse_constraint_order("red-black"), ConstraintOrder::red_black);
  EXPECT_THROW(parse_constraint_order("random"), std::invalid_argument);
}

// Red-black written out plainly, as documented: even springs, odd springs, the closing spring; the
// library's version must give exactly these bits.
void red_black_reference(DropletState* s, double d0, double strain, int passes) {
  const int n = s->size();
  const double dmax = (1 + strain) * d0, dmin = (1 - strain) * d0;
  auto fix = [&](int i, int j) {
    const double dx = s->x[j] - s->x[i], dy = s->y[j] - s->y[i];
    const double d2 = dx * dx + dy * dy;
    if (d2 <= dmax * dmax && d2 >= dmin * dmin) return;
    const double d = std::sqrt(d2);
    if (d == 0) return;
    const double c = 0.5 * (d - (d2 > dmax * dmax ? dmax : dmin)) / d;
    s->x[i] += c * dx;
    s->y[i] += c * dy;
    s->x[j] -= c * dx;
    s->y[j] -= c * dy;
  };
  for (int p = 0; p < passes; ++p) {
    for (int i = 0; i + 1 < n; i += 2) fix(i, i + 1);
    for (int i = 1; i + 1 < n; i += 2) fix(i, i + 1);
    fix(n - 1, 0);
  }
}

TEST(Droplet, RedBlackIsExactlyTheDocumentedOrder) {
  for (int masses : {8, 9, 16, 40, 41, 128}) {
    DropletParams p;
    p.masses = masses;
    DropletState a = test::jiggled_ring(masses, static_cast<std::uint64_t>(masses));
    DropletState b = a;
    apply_length_constraint(&a, p.rest_length(), p.max_strain, 3, ConstraintOrder::red_black);
    red_black_reference(&b, p.rest_length(), p.max_strain, 3);
    EXPECT_EQ(a.x, b.x) << masses << " masses";
    EXPECT_EQ(a.y, b.y) << masses << " masses";
  }
}

// The sequential order written out plainly: springs (0,1), (1,2), ..., (n-1, 0), each seeing the
// previous one's correction. The library's version (which keeps the shared mass in a register and
// computes 0.5 (d - target) / d as (d - target) / (d + d)) must give exactly these bits.
TEST(Droplet, SequentialIsExactlyTheDocumentedOrder) {
  for (int masses : {8, 9, 16, 40, 41, 128}) {
    DropletParams p;
    p.masses = masses;
    DropletState a = test::jiggled_ring(masses, static_cast<std::uint64_t>(masses) + 100);
    DropletState b = a;
    const int moved = apply_length_constraint(&a, p.rest_length(), p.max_strain, 3);
    const double d0 = p.rest_length(), dmax = (1 + p.max_strain) * d0, dmin = (1 - p.max_strain) * d0;
    int expected = 0;
    for (int pass = 0; pass < 3; ++pass) {
      int changed = 0;
      for (int i = 0; i < masses; ++i) {
        const int j = (i + 1) % masses;
        const double dx = b.x[j] - b.x[i], dy = b.y[j] - b.y[i];
        const double d2 = dx * dx + dy * dy;
        if (d2 <= dmax * dmax && d2 >= dmin * dmin) continue;
        const double d = std::sqrt(d2);
        const double c = 0.5 * (d - (d2 > dmax * dmax ? dmax : dmin)) / d;
        b.x[i] += c * dx;
        b.y[i] += c * dy;
        b.x[j] -= c * dx;
        b.y[j] -= c * dy;
        ++changed;
      }
      expected += changed;
      if (changed == 0) break;
    }
    EXPECT_EQ(moved, expected) << masses << " masses";
    EXPECT_EQ(a.x, b.x) << masses << " masses";
    EXPECT_EQ(a.y, b.y) << masses << " masses";
  }
}

// A spring whose squared length is just above dmax^2 can have a square root that rounds to dmax
// exactly. It is stretched, not compressed: it must stay at dmax, not be pulled down to dmin (which
// deciding on "d > dmax" did, a 20 % jolt to one spring in about one step of 10^10).
TEST(Droplet, ASpringWhoseLengthRoundsToTheLimitIsNotPulledToTheOtherLimit) {
  const double d0 = 1.0, strain = 0.1, dmax = (1 + strain) * d0, dmax2 = dmax * dmax;
  double dy = 0;
  for (int k = 1; k < 100000 && dy == 0; ++k) {
    const double t = 1e-10 * k, d2 = dmax * dmax + t * t;
    if (d2 > dmax2 && std::sqrt(d2) == dmax) dy = t;
  }
  ASSERT_GT(dy, 0) << "no spring length with d^2 > dmax^2 and sqrt(d^2) == dmax found";
  for (ConstraintOrder order : {ConstraintOrder::sequential, ConstraintOrder::red_black}) {
    DropletState s;
    s.resize(3);
    s.x = {0, dmax, 0.5 * dmax};  // edge 0-1 of length dmax by its rounded root; the others ~1.0
    s.y = {0, dy, 0.8};
    s.px = s.x;
    s.py = s.y;
    apply_length_constraint(&s, d0, strain, 1, order);
    EXPECT_NEAR(spring_length(s, 0), dmax, 1e-12) << to_string(order);
  }
}

}  // namespace
}  // namespace softdrop
