#include "softdrop/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "fixtures.hpp"
#include "sim/lane_policy.hpp"

namespace softdrop {
namespace {

TEST(Simulation, FreeFallWithoutGrainsHasTortuosityOneAndFollowsTheParabola) {
  DropletParams p;
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  RunOptions o;
  o.path_interval = 50;
  const RunSummary r = sim.run(123.0, o);
  ASSERT_EQ(r.outcome, Outcome::passed) << r.reason;
  EXPECT_NEAR(r.tortuosity, 1.0, 1e-9);
  EXPECT_TRUE(r.touched.empty());
  // Centre of mass: y0 + g t^2 / 2 (internal forces cancel), x constant; to position Verlet's
  // rounding, which grows as steps^1.5 (about 5e-7 after this fall's 60 000 steps).
  for (std::size_t k = 0; k < r.path_t.size(); ++k) {
    const double t = r.path_t[k];
    EXPECT_NEAR(r.path_y[k], r.start_y + 0.5 * p.gravity * t * t, 1e-8 * (1 + std::abs(r.start_y))) << "t = " << t;
    EXPECT_NEAR(r.path_x[k], 123.0, 1e-9);
  }
  // Fall time from the start height through H = 500.
  const double expected_t = std::sqrt(2 * r.start_y / -p.gravity);
  EXPECT_NEAR(static_cast<double>(r.steps) * p.dt, expected_t, 2 * p.dt);
  // The on-line path length agrees with the polyline of the recorded path.
  EXPECT_NEAR(polyline_tortuosity(r.path_x, r.path_y, empty.height), 1.0, 1e-9);
}

TEST(Simulation, RestingDropletWithoutGravityKeepsItsAreaAndPlace) {
  DropletParams p;
  p.gravity = 0;
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  sim.place(250, 250);
  const double a0 = ring_area(sim.state());
  double min_a = a0, max_a = a0;
  for (int k = 0; k < 100000; ++k) {
    ASSERT_TRUE(sim.step());
    if (k % 100 == 0) {
      const double a = ring_area(sim.state());
      min_a = std::min(min_a, a);
      max_a = std::max(max_a, a);
    }
  }
  EXPECT_GT(min_a, 0.995 * a0);
  EXPECT_LT(max_a, 1.005 * a0);
  double cx, cy;
  sim.centre_of_mass(&cx, &cy);
  // Only rounding moves it: internal forces cancel (about 5e-9 after 1e5 steps).
  EXPECT_NEAR(cx, 250, 1e-7);
  EXPECT_NEAR(cy, 250, 1e-7);
}

TEST(Simulation, SqueezesThroughAPoreNarrowerThanItsDiameter) {
  DropletParams p;
  const Medium pore = test::pore_of_three_grains();
  ASSERT_LT(pore.grains[1].x - pore.grains[0].x - 2 * 16, 2 * p.radius);
  Simulation sim(p, pore);
  RunOptions o;
  o.area_interval = 10;
  o.check_interval = 1;
  const RunSummary r = sim.run(100.0, o);
  ASSERT_EQ(r.outcome, Outcome::passed) << r.reason;
  EXPECT_GE(r.tortuosity, 1.0);
  // It touched both pore grains and changed its area on the way.
  EXPECT_TRUE(std::binary_search(r.touched.begin(), r.touched.end(), 0));
  EXPECT_TRUE(std::binary_search(r.touched.begin(), r.touched.end(), 1));
  EXPECT_LT(r.min_area_ratio, 0.95);
  EXPECT_LE(r.max_penetration, 0.25 * p.radius);
  EXPECT_FALSE(r.grain_inside_ring);
}

TEST(Simulation, RowOfGrainsStopsTheDroplet) {
  DropletParams p;
  Medium floor{200, 200, true, {}, nullptr};
  for (int i = 0; i < 10; ++i) floor.grains.push_back({10.0 + 20.0 * i, 100, 12});
  Simulation sim(p, floor);
  RunOptions o;
  o.stuck_window = 0.1;
  o.rest_window = 0;  // the stuck test alone (the rest test, which would end it sooner, is tested below)
  const RunSummary r = sim.run(37.0, o);
  EXPECT_EQ(r.outcome, Outcome::stuck) << r.reason;
  EXPECT_NE(r.reason.find("moved down"), std::string::npos) << r.reason;
  double cx, cy;
  sim.centre_of_mass(&cx, &cy);
  EXPECT_GT(cy, 100);  // resting on top of the row
  EXPECT_FALSE(r.touched.empty());
}

TEST(Simulation, TheRestTestEndsAStuckDropletEarlyAndChangesNothingElse) {
  DropletParams p;
  Medium floor{200, 200, true, {}, nullptr};
  for (int i = 0; i < 10; ++i) floor.grains.push_back({10.0 + 20.0 * i, 100, 12});
  RunOptions rest_test;  // the defaults: the stuck test and the rest test
  ASSERT_EQ(rest_test.rest_window, 0.05);
  ASSERT_EQ(rest_test.rest_distance, 0.1);
  RunOptions stuck_test = rest_test;  // the stuck test alone
  stuck_test.rest_window = 0;
  const RunSummary slow = Simulation(p, floor).run(37.0, stuck_test);
  const RunSummary fast = Simulation(p, floor).run(37.0, rest_test);
  ASSERT_EQ(slow.outcome, Outcome::stuck) << slow.reason;
  ASSERT_EQ(fast.outcome, Outcome::stuck) << fast.reason;
  EXPECT_NE(fast.reason.find("at rest"), std::string::npos) << fast.reason;
  EXPECT_LT(fast.steps, slow.steps / 2);
  // A droplet that passes is untouched by it: the same steps, path and tortuosity to the bit.
  const Medium pore = test::pore_of_three_grains();
  const RunSummary a = Simulation(p, pore).run(100.0, stuck_test);
  const RunSummary b = Simulation(p, pore).run(100.0, rest_test);
  ASSERT_EQ(a.outcome, Outcome::passed) << a.reason;
  EXPECT_EQ(b.outcome, Outcome::passed) << b.reason;
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.tortuosity, b.tortuosity);
  rest_test.rest_window = -1;
  std::string why;
  EXPECT_FALSE(rest_test.IsValid(&why));
  EXPECT_NE(why.find("rest-window = -1"), std::string::npos) << why;
}

TEST(Simulation, StepBudgetEndsInTimeout) {
  DropletParams p;
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  RunOptions o;
  o.max_steps = 100;
  const RunSummary r = sim.run(50, o);
  EXPECT_EQ(r.outcome, Outcome::timeout);
  EXPECT_EQ(r.steps, 100);
}

TEST(Simulation, NaNStateEndsInDivergedNotACrash) {
  DropletParams p;
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  sim.place_above(50);
  sim.mutable_state().x[3] = std::nan("");
  const RunSummary r = sim.run_from_current({});
  EXPECT_EQ(r.outcome, Outcome::diverged);
  EXPECT_EQ(r.steps, 1);
}

TEST(Simulation, SolidWallsKeepTheDropletInTheBox) {
  DropletParams p;
  Medium box{100, 300, false, {}, nullptr};
  box.grains.push_back({80, 150, 30});  // deflects the droplet towards the right wall
  Simulation sim(p, box);
  RunOptions o;
  o.path_interval = 1;
  const RunSummary r = sim.run(70, o);
  ASSERT_NE(r.outcome, Outcome::diverged) << r.reason;
  for (double x : r.path_x) {
    EXPECT_GT(x, p.radius * 0.5);
    EXPECT_LT(x, 100 - p.radius * 0.5);
  }
}

TEST(Simulation, GrainsNarrowerThanAnEdgeAreRefused) {
  DropletParams p;  // longest edge 2 R sin(pi / N) = 1.57
  const Medium tiny{100, 100, true, {{50, 50, 1.0}}, nullptr};
  EXPECT_THROW(Simulation(p, tiny), std::invalid_argument);
  p.masses = 80;  // longest edge 0.785: fine
  EXPECT_NO_THROW(Simulation(p, tiny));
}

TEST(Simulation, PolylineTortuosityInterpolatesCrossings) {
  // Enters at (0, 10), goes right 10, leaves at (10, 0): length 10 + 10 over H = 10.
  const std::vector<double> xs = {0, 0, 10, 10}, ys = {15, 5, 5, -5};
  EXPECT_DOUBLE_EQ(polyline_tortuosity(xs, ys, 10), 2.0);
}

}  // namespace
}  // namespace softdrop

namespace softdrop {
namespace {

TEST(Simulation, ACancelHookStopsTheRunAndOtherwiseChangesNothing) {
  const Medium m = test::pore_of_three_grains();
  DropletParams p;
  RunOptions plain, watched, stopping;
  int polls = 0;
  watched.cancelled = [&] {
    ++polls;
    return false;
  };
  stopping.cancelled = [] { return true; };
  Simulation a(p, m), b(p, m), c(p, m);
  const RunSummary ra = a.run(100, plain), rb = b.run(100, watched);
  EXPECT_EQ(ra.tortuosity, rb.tortuosity);
  EXPECT_EQ(ra.steps, rb.steps);
  EXPECT_EQ(a.state_hash(), b.state_hash());
  EXPECT_EQ(polls, ra.steps / plain.check_interval);
  EXPECT_THROW(c.run(100, stopping), RunCancelled);
}

TEST(Simulation, StepsThatReuseContactTestsEqualStepsThatLookEverythingUp) {
  // The contact limit records which grains each mass is inside, for the next step's collisions,
  // and how far each mass is from every other grain of its cell, so that it can skip the tests
  // while the mass stays that close to where it was. A simulation made afresh from the same state
  // has neither record: its step must give the same state and forces to the bit, including after
  // masses are moved from outside. In the second scene 12 grains of growing radii touch the same
  // top point, so that a mass resting there is inside more grains than the record holds (8). In
  // the third, an open random medium, masses cross wide pores, where their anchor balls reach
  // past their cells' edges into the grid's halo.
  Medium pile{200, 200, true, {}, nullptr};
  for (int k = 0; k < 12; ++k) pile.grains.push_back({100.0, 100.0 - (15.0 + k), 15.0 + k});
  MediumOptions open_options;
  open_options.porosity = 0.8;
  open_options.width = open_options.height = 300;
  open_options.seed = 2;
  open_options.r_min = test::kBalloonRMin, open_options.r_max = test::kBalloonRMax;
  const Medium open = generate_medium(open_options);
  auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
    return a.size() == b.size();
  };
  const DropletParams p = test::balloon_droplet();  // (the scenes and step counts were laid out for it)
  for (const Medium& medium : {test::pore_of_three_grains(), pile, open}) {
    SCOPED_TRACE(medium.grains.size() == 3 ? "pore" : medium.grains.size() == 12 ? "pile" : "open");
    Simulation sim(p, medium);
    sim.place_above(100);
    int in_contact = 0, moved = 0;
    for (int k = 0; k < 3000; ++k) {
      if (k % 97 == 50) {  // move one mass (not its velocity): it must be looked up again
        DropletState& s = sim.mutable_state();
        const std::size_t i = static_cast<std::size_t>(k) % s.x.size();
        s.x[i] += 0.25;
        s.px[i] += 0.25;
        s.y[i] -= 0.25;
        s.py[i] -= 0.25;
        ++moved;
      }
      Simulation fresh(p, medium);
      fresh.mutable_state() = sim.state();
      const bool a_ok = sim.step(), b_ok = fresh.step();
      ASSERT_EQ(a_ok, b_ok) << "step " << k;
      const DropletState &a = sim.state(), &b = fresh.state();
      ASSERT_TRUE(same(a.fx, b.fx) && same(a.fy, b.fy)) << "forces differ at step " << k;
      ASSERT_TRUE(same(a.x, b.x) && same(a.y, b.y) && same(a.px, b.px) && same(a.py, b.py))
          << "positions differ after step " << k;
      in_contact += sim.last_penetration() > 0;
    }
    EXPECT_GT(in_contact, 120) << "the droplet must spend a while inside grains";
    EXPECT_GT(moved, 30);
  }
}

TEST(Simulation, RecordedContactForcesEqualForcesComputedFromTheRecords) {
  // The contact limit leaves the next collisions the force on each mass it found inside one disc
  // (computed eight at a time, at the positions and velocities it tested), the grain touched and
  // the deepest depth, with a list of the masses it did not cover; any change of the state in
  // between (here mutable_state(), before every step of the second droplet) makes the collisions
  // compute every contact from the records instead. Both must give the same forces, positions,
  // depth and touched set, step by step, in a pore, across the periodic seam, by the walls of a
  // box and in an open random medium.
  const Medium seam{200, 200, true, {{0.0, 120.0, 18.0}, {196.0, 60.0, 14.0}, {30.0, 40.0, 12.0}}, nullptr};
  const Medium walled{120, 200, false, {{8.0, 120.0, 14.0}, {112.0, 80.0, 14.0}}, nullptr};
  MediumOptions open_options;
  open_options.porosity = 0.8;
  open_options.width = open_options.height = 300;
  open_options.seed = 2;
  open_options.r_min = test::kBalloonRMin, open_options.r_max = test::kBalloonRMax;
  const Medium open = generate_medium(open_options);
  const Medium pore = test::pore_of_three_grains();
  struct Scene {
    const char* name;
    const Medium* medium;
    double x0;
  };
  const Scene scenes[] = {{"pore", &pore, 100}, {"seam", &seam, 0.5}, {"walled", &walled, 14}, {"open", &open, 150}};
  auto bits = [](const DropletState& s) {
    std::vector<std::uint64_t> b;
    for (const std::vector<double>* v : {&s.fx, &s.fy, &s.x, &s.y, &s.px, &s.py})
      for (double d : *v) b.push_back(std::bit_cast<std::uint64_t>(d));
    return b;
  };
  const DropletParams p = test::balloon_droplet();  // (the scenes and step counts were laid out for it)
  for (const Scene& scene : scenes) {
    SCOPED_TRACE(scene.name);
    Simulation recorded(p, *scene.medium), recomputed(p, *scene.medium);
    recorded.place_above(scene.x0);
    recomputed.place_above(scene.x0);
    int touching = 0;
    for (int k = 0; k < 3000; ++k) {
      (void)recomputed.mutable_state();
      ASSERT_EQ(recorded.step(), recomputed.step()) << "step " << k;
      ASSERT_EQ(bits(recorded.state()), bits(recomputed.state())) << "step " << k;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(recorded.last_penetration()),
                std::bit_cast<std::uint64_t>(recomputed.last_penetration()))
          << "step " << k;
      touching += recorded.last_penetration() > 0;
    }
    RunOptions one;
    one.max_steps = 1;
    const RunSummary a = recorded.run_from_current(one), b = recomputed.run_from_current(one);
    EXPECT_EQ(a.touched, b.touched);
    EXPECT_FALSE(a.touched.empty());
    EXPECT_GT(touching, 120) << "the droplet must spend a while inside grains";
  }
}

TEST(Simulation, TheContactLimitGivesTheSameBitsEightMassesAtATime) {
  // With AVX or AVX-512 the contact limit tests the masses free in their anchor's ball, or inside
  // its one disc, eight at a time (src/sim/contact_limit_kernels.inc); the scalar width tests them one by
  // one. Every step must leave the same state and records: compared by the next step's forces
  // (the collisions read the records) and the positions, step by step, over contact-heavy runs:
  // the pore, a mass resting inside 12 discs at once, a droplet that lands on a grain across the
  // periodic seam (masses at x < 0 and x > W, where the wrapped position is not x, and discs
  // whose centres lie across the seam), one that meets grains by the walls of a box, and the pore
  // reached a period away.
  Medium pile{200, 200, true, {}, nullptr};
  for (int k = 0; k < 12; ++k) pile.grains.push_back({100.0, 100.0 - (15.0 + k), 15.0 + k});
  const Medium seam{200, 200, true, {{0.0, 120.0, 18.0}, {196.0, 60.0, 14.0}, {30.0, 40.0, 12.0}}, nullptr};
  const Medium walled{120, 200, false, {{8.0, 120.0, 14.0}, {112.0, 80.0, 14.0}}, nullptr};
  struct Scene {
    const char* name;
    const Medium* medium;
    double x0;
  };
  const Medium pore = test::pore_of_three_grains();
  // The pore a period over and a period back: a droplet that has crossed the seam keeps its
  // unwrapped positions, so all its masses are tested at wrapped positions, x - W floor(x / W).
  const Scene scenes[] = {{"pore", &pore, 100},    {"pile", &pile, 100},      {"seam", &seam, 0.5},
                          {"walled", &walled, 14}, {"pore over", &pore, 300}, {"pore back", &pore, -100}};
  auto bits = [](const std::vector<double>& v) {
    std::vector<std::uint64_t> b;
    for (double d : v) b.push_back(std::bit_cast<std::uint64_t>(d));
    return b;
  };
  const DropletParams p = test::balloon_droplet();  // (the scenes and step counts were laid out for it)
  test::LackedWidths lacked;
  for (const Scene& scene : scenes) {
    SCOPED_TRACE(scene.name);
    std::vector<std::vector<std::uint64_t>> reference;  // per step: fx, fy, x, y, px, py
    int touching = 0, across = 0;                       // steps in a grain; of those, with a mass outside [0, W]
    for (VectorWidth width : test::kVectorWidths) {
      const test::VectorWidthLimit limit(width);
      if (!lacked.has(limit, width)) continue;
      SCOPED_TRACE(static_cast<int>(width));
      Simulation sim(p, *scene.medium);
      sim.place_above(scene.x0);
      for (int k = 0; k < 4000; ++k) {
        sim.step();
        const DropletState& s = sim.state();
        std::vector<std::uint64_t> now;
        for (const std::vector<double>* v : {&s.fx, &s.fy, &s.x, &s.y, &s.px, &s.py}) {
          const std::vector<std::uint64_t> b = bits(*v);
          now.insert(now.end(), b.begin(), b.end());
        }
        if (width == VectorWidth::scalar) {
          reference.push_back(std::move(now));
          const bool in = sim.last_penetration() > 0;
          touching += in;
          across +=
              in && std::any_of(s.x.begin(), s.x.end(), [&](double x) { return x < 0 || x > scene.medium->width; });
        } else {
          ASSERT_EQ(now, reference[static_cast<std::size_t>(k)]) << "step " << k;
        }
      }
    }
    EXPECT_GT(touching, 120) << "the droplet must spend a while inside grains";
    if (scene.medium == &seam) {
      EXPECT_GT(across, 250) << "and, at the seam, across it";
    }
    if (scene.x0 < 0 || scene.x0 > scene.medium->width) {
      EXPECT_EQ(across, touching) << "a period away, every mass is outside [0, W]";
    }
  }
  if (lacked.any()) GTEST_SKIP() << lacked.message();
}

}  // namespace
}  // namespace softdrop
