#include "softdrop/droplet.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "fixtures.hpp"
#include "sim/lane_policy.hpp"
#include "sim/step_driver.hpp"
#include "softdrop/simulation.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {

TEST(Droplet, InflatedRingIsCounterClockwiseWithTheStatedArea) {
  const DropletParams p = test::balloon_droplet();  // placed at its stretch limit, the inflated ring
  DropletState s;
  place_droplet(p, 3, 4, &s);
  EXPECT_NEAR(ring_area(s), p.inflated_area(), 1e-9 * p.inflated_area());
  EXPECT_GT(ring_area(s), 0);
  EXPECT_NEAR(test::spring_length(s, 0), (1 + p.max_strain) * p.rest_length(), 1e-12);
  EXPECT_FALSE(ring_self_intersects(s));
  EXPECT_TRUE(ring_contains(s, 3, 4));
  EXPECT_FALSE(ring_contains(s, 3 + 1.01 * p.radius, 4));
}

// The ring starts at rest: a balloon at its stretch limit, R itself, to the bit; a ring whose
// springs carry the tension (the defaults) on the N-gon where they balance the gas, so it does not
// breathe; a weak gas leaves the springs at about their rest length.
TEST(Droplet, TheRingStartsWhereItsSpringsBalanceTheGas) {
  const DropletParams balloon = test::balloon_droplet();
  EXPECT_EQ(balloon.resting_radius(), balloon.radius);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(balloon.resting_area()),
            std::bit_cast<std::uint64_t>(balloon.inflated_area()));

  DropletParams springs;  // the defaults: the gas holds the springs at 5 % strain, well inside the limit
  springs.gravity = 0, springs.viscosity = 0;
  const double rho = springs.resting_radius(), s = std::sin(M_PI / springs.masses);
  EXPECT_LT(rho, springs.radius);
  const double strain = 2 * rho * s / springs.rest_length() - 1;
  EXPECT_GT(strain, 0.03);
  EXPECT_LT(strain, 0.06);
  // Per mass: the gas's 2 nRT / (N rho) out, the two springs' 2 k_s (d - d0) s in.
  const double out = 2 * springs.nrt / (springs.masses * rho);
  const double in = 2 * springs.ks * (2 * rho * s - springs.rest_length()) * s;
  EXPECT_NEAR(in, out, 1e-12 * out);
  const Medium empty{500, 500, true, {}, nullptr};
  Simulation sim(springs, empty);
  EXPECT_NEAR(sim.area(), springs.resting_area(), 1e-12 * springs.resting_area());
  EXPECT_EQ(sim.initial_area(), springs.resting_area());
  double least = sim.area(), most = sim.area();
  for (int k = 0; k < 5000; ++k) {  // some 80 periods of the breathing mode
    ASSERT_TRUE(sim.step());
    least = std::min(least, sim.area()), most = std::max(most, sim.area());
  }
  // Started at R instead, the ring would swing between about 0.90 and 1.0 of its inflated area.
  EXPECT_LT((most - least) / springs.resting_area(), 1e-6);

  DropletParams weak = springs;
  weak.nrt = 1;
  EXPECT_NEAR(2 * weak.resting_radius() * s, weak.rest_length(), 1e-6 * weak.rest_length());
  DropletParams no_springs = springs;
  no_springs.ks = 0;
  EXPECT_EQ(no_springs.resting_radius(), no_springs.radius);
}

TEST(Droplet, ReversedRingHasNegativeAreaAndFigureEightIntersects) {
  DropletParams p;
  DropletState s;
  place_droplet(p, 0, 0, &s);
  std::reverse(s.x.begin(), s.x.end());
  std::reverse(s.y.begin(), s.y.end());
  EXPECT_LT(ring_area(s), 0);
  // Twist: swap the halves' y to make a figure eight.
  place_droplet(p, 0, 0, &s);
  for (int i = 0; i < s.size() / 2; ++i) s.y[i] = -s.y[i];
  EXPECT_TRUE(ring_self_intersects(s));
}

// The self-intersection test written out plainly, pair by pair with the modulo of the ring's
// indices; counts the crossing pairs, and those with the closing edge (n - 1, 0) in *closing.
int crossing_pairs(const DropletState& s, int* closing) {
  auto cross = [](double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  };
  const int n = s.size();
  int count = 0;
  *closing = 0;
  for (int i = 0; i < n; ++i) {
    const int i1 = (i + 1) % n;
    for (int j = i + 2; j < n; ++j) {
      const int j1 = (j + 1) % n;
      if (j1 == i) continue;
      const double d1 = cross(s.x[i], s.y[i], s.x[i1], s.y[i1], s.x[j], s.y[j]);
      const double d2 = cross(s.x[i], s.y[i], s.x[i1], s.y[i1], s.x[j1], s.y[j1]);
      const double d3 = cross(s.x[j], s.y[j], s.x[j1], s.y[j1], s.x[i], s.y[i]);
      const double d4 = cross(s.x[j], s.y[j], s.x[j1], s.y[j1], s.x[i1], s.y[i1]);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0) {
        ++count;
        *closing += j == n - 1;
      }
    }
  }
  return count;
}

TEST(Droplet, SelfIntersectionMatchesThePlainPairByPairTest) {
  // Rings from gently to wildly jiggled, of sizes with every remainder, crossing or not, and some
  // whose only crossing is with the closing edge; at every vector width (AVX tests four edges at
  // once).
  int crossing = 0, clear = 0, only_closing = 0;
  for (VectorWidth width : test::kVectorWidths) {
    const test::VectorWidthLimit limit(width);
    for (int masses : {3, 4, 5, 6, 8, 13, 40}) {
      for (double amplitude : {0.5, 3.0, 8.0}) {
        for (std::uint64_t seed = 0; seed < 150; ++seed) {
          const DropletState s =
              test::jiggled_ring(masses, 1000 * seed + static_cast<std::uint64_t>(masses), amplitude);
          int closing = 0;
          const int pairs = crossing_pairs(s, &closing);
          ASSERT_EQ(ring_self_intersects(s), pairs > 0) << masses << " masses, amplitude " << amplitude << ", seed "
                                                        << seed << ", vector width " << static_cast<int>(width);
          (pairs > 0 ? crossing : clear) += 1;
          only_closing += pairs > 0 && pairs == closing;
        }
      }
    }
  }
  EXPECT_GT(crossing, 400);
  EXPECT_GT(clear, 400);
  EXPECT_GT(only_closing, 20);
}

TEST(Droplet, InternalForcesSumToZero) {
  // Gravity off, no grains: springs, pressure and viscosity are internal and must cancel.
  DropletParams p;
  p.gravity = 0;
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  sim.place(250, 250);
  Rng rng(7);
  DropletState& s = sim.mutable_state();
  for (int i = 0; i < s.size(); ++i) {  // a deformed ring moving with random velocities
    s.x[i] += rng.uniform(-1, 1);
    s.y[i] += rng.uniform(-1, 1);
    s.px[i] = s.x[i] - rng.uniform(-0.1, 0.1);
    s.py[i] = s.y[i] - rng.uniform(-0.1, 0.1);
  }
  sim.compute_forces();
  double sx = 0, sy = 0, scale = 0;
  for (int i = 0; i < s.size(); ++i) {
    sx += s.fx[i];
    sy += s.fy[i];
    scale += std::abs(s.fx[i]) + std::abs(s.fy[i]);
  }
  ASSERT_GT(scale, 1e6);  // the forces are large, so the cancellation is meaningful
  EXPECT_LT(std::abs(sx), 1e-12 * scale);
  EXPECT_LT(std::abs(sy), 1e-12 * scale);
}

// The viscosity stage's forces on a ring moving as a whole (translation u, rotation omega) and
// dilating uniformly at rate delta, from rest positions and one step's displacement.
std::vector<double> viscous_forces(double dilation_share, double delta, double* torque, double* net) {
  DropletParams p;
  p.gravity = 0;
  p.viscosity_dilation = dilation_share;
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  sim.place(250, 250);
  DropletState& s = sim.mutable_state();
  const double dt = p.dt, omega = 40, ux = 300, uy = -200;
  for (int i = 0; i < s.size(); ++i) {
    const double rx = s.x[i] - 250, ry = s.y[i] - 250;
    s.px[i] = s.x[i] - dt * (ux - omega * ry + delta * rx);
    s.py[i] = s.y[i] - dt * (uy + omega * rx + delta * ry);
  }
  run_stage(sim, StepStage::gravity);  // zero forces (no gravity)
  run_stage(sim, StepStage::viscosity);
  std::vector<double> f;
  *torque = *net = 0;
  for (int i = 0; i < s.size(); ++i) {
    f.push_back(s.fx[i]);
    f.push_back(s.fy[i]);
    *torque += (s.x[i] - 250) * s.fy[i] - (s.y[i] - 250) * s.fx[i];
    *net += std::hypot(s.fx[i], s.fy[i]);
  }
  return f;
}

TEST(Droplet, TheViscositySparesTheRingsDilationOnlyWhenAsked) {
  const DropletParams p;
  const double delta = 25;  // 1/time
  double torque = 0, size = 0;
  // Damped as any deformation: each mass feels -m rate delta r_i (rate: viscous_rate(), nu's
  // coefficient for the step).
  std::vector<double> f = viscous_forces(1.0, delta, &torque, &size);
  const double expected = p.mass * p.viscous_rate() * delta * p.resting_radius();  // (the ring starts at rest)
  for (std::size_t k = 0; k < f.size(); k += 2) EXPECT_NEAR(std::hypot(f[k], f[k + 1]), expected, 1e-6 * expected);
  EXPECT_LT(std::abs(torque), 1e-9 * size * p.radius);
  // Spared: translation, rotation and dilation are all "rigid" now, so no force at all.
  f = viscous_forces(0.0, delta, &torque, &size);
  for (double v : f) EXPECT_LT(std::abs(v), 1e-6 * expected);
  // Half spared: half the force.
  f = viscous_forces(0.5, delta, &torque, &size);
  for (std::size_t k = 0; k < f.size(); k += 2)
    EXPECT_NEAR(std::hypot(f[k], f[k + 1]), 0.5 * expected, 1e-6 * expected);
}

TEST(Droplet, SpringForcesHaveTheSameBitsAtEveryVectorWidth) {
  // The springs go eight at a time with AVX or AVX-512 (the last eight overlapping the ones before)
  // from 9 masses on; each lane must do the scalar operations. Their forces are too small beside
  // the pressure and the constraint for a rounding difference to reach the positions (the golden
  // hashes cannot see it), so they are compared here directly, for rings too small for a group,
  // of exactly one, two and three groups and every overlap between, with a zero-length spring
  // (two masses on one point) among them.
  DropletParams p;
  p.gravity = 0;
  const Medium empty = test::empty_medium();
  for (int masses = 8; masses <= 26; ++masses) {
    p.masses = masses;
    Simulation sim(p, empty);
    sim.place(250, 250);
    Rng rng(static_cast<std::uint64_t>(masses));
    DropletState& s = sim.mutable_state();
    for (int i = 0; i < s.size(); ++i) {
      s.x[i] += rng.uniform(-1, 1);
      s.y[i] += rng.uniform(-1, 1);
      s.px[i] = s.x[i] - rng.uniform(-0.1, 0.1);
      s.py[i] = s.y[i] - rng.uniform(-0.1, 0.1);
    }
    s.x[5] = s.x[4];  // spring (4, 5) has no length
    s.y[5] = s.y[4];
    std::vector<std::vector<double>> forces;
    for (VectorWidth width : test::kVectorWidths) {
      const test::VectorWidthLimit limit(width);
      std::fill(s.fx.begin(), s.fx.end(), 0.0);
      std::fill(s.fy.begin(), s.fy.end(), 0.0);
      run_stage<StepStage::springs>(sim);
      forces.push_back(s.fx);
      forces.back().insert(forces.back().end(), s.fy.begin(), s.fy.end());
    }
    for (std::size_t w = 1; w < forces.size(); ++w)
      for (std::size_t i = 0; i < forces[0].size(); ++i)
        ASSERT_EQ(std::bit_cast<std::uint64_t>(forces[w][i]), std::bit_cast<std::uint64_t>(forces[0][i]))
            << masses << " masses, width #" << w << ", force component " << i;
    EXPECT_NE(s.fx[4], 0.0) << "the masses around the zero-length spring feel their other springs";
  }
}

TEST(Droplet, ParamsValidation) {
  std::string why;
  DropletParams p;
  EXPECT_TRUE(p.IsValid(&why)) << why;
  p.dt = 0;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("dt"), std::string::npos);
  p = {};
  p.radius = -1;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("radius"), std::string::npos);
  p = {};
  p.nrt = std::nan("");
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("nrt"), std::string::npos);
  p = {};
  p.dt = 1e-3;  // far too large for the default k_c at m = 1
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("dt"), std::string::npos);
  p = {};
  p.masses = 100000000;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("masses"), std::string::npos);
}

}  // namespace
}  // namespace softdrop