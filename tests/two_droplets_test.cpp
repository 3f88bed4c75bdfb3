// Two droplets one after the other (simulation.hpp): the rings never interpenetrate, a collision
// keeps the pair's momentum, rings that never meet run as they would alone, to the bit, and a bad
// second droplet is refused naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"
#include "fixtures.hpp"
#include "sim/droplet_runtime.hpp"
#include "sim/ring_contact.hpp"
#include "sim/ring_group_step.hpp"
#include "sim/two_droplet_run.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

// Whether a mass of ring p is inside ring e, whose x is shifted by `shift` (a periodic copy).
bool mass_inside(const DropletState& p, const DropletState& e, double shift) {
  DropletState moved = e;
  for (double& x : moved.x) x += shift;
  for (int i = 0; i < p.size(); ++i)
    if (ring_contains(moved, p.x[i], p.y[i])) return true;
  return false;
}

// The pair's momentum per unit mass and time step: the sum of every mass's displacement x - px.
void momentum(const DropletState& a, const DropletState& b, double* px, double* py) {
  *px = *py = 0;
  for (const DropletState* s : {&a, &b})
    for (int i = 0; i < s->size(); ++i) {
      *px += s->x[i] - s->px[i];
      *py += s->y[i] - s->py[i];
    }
}

// The displacements a mass at velocity (vx, vy) takes a step.
void set_velocity(DropletState* s, double vx, double vy, double dt) {
  for (int i = 0; i < s->size(); ++i) {
    s->px[i] = s->x[i] - vx * dt;
    s->py[i] = s->y[i] - vy * dt;
  }
}

TEST(TwoDroplets, AHeadOnCollisionInFreeFallKeepsThePairsMomentumAndNoMassGetsInside) {
  // No grains: two droplets thrown at each other (at different speeds, and off centre, so that
  // the collision turns them), falling together. Every internal force and every ring-ring force
  // and correction comes in opposite pairs: the pair's momentum is gravity's alone, to rounding.
  // At the faster speeds the penalty cannot stop the rings within max_depth, and the limit works.
  const Medium box = test::empty_medium(500, 500);
  const DropletParams p;
  for (const auto& [va, vb] : {std::pair{900.0, -1500.0}, std::pair{12000.0, -15000.0}}) {
    SCOPED_TRACE("speeds " + std::to_string(va) + ", " + std::to_string(vb));
    Simulation a(p, box), b(a);
    // Near the origin, where the positions' rounding (which any Verlet step has) is smallest.
    a.place(-12, 40);
    b.place(-12 + 2 * p.radius + 4, 43);
    const double dt = p.dt;
    set_velocity(&a.mutable_state(), va, 0, dt);
    set_velocity(&b.mutable_state(), vb, 0, dt);
    double px0, py0;
    momentum(a.state(), b.state(), &px0, &py0);
    const int n = a.state().size() + b.state().size();
    RingContactScratch scratch;
    std::vector<DropletState*> group_rings;
    std::vector<int> corrections;
    Simulation* sims[2] = {&a, &b};
    std::int64_t touching = 0, limited = 0;
    double worst_x = 0, worst_y = 0;
    const int steps = 3000;  // 0.018 time units: they meet within 0.002 and rebound
    for (int k = 1; k <= steps; ++k) {
      RingPair pair{0, 1, &scratch, 0};
      RingGroup rings{sims, 2, &group_rings, &corrections, &pair, 1};
      run_stages(rings);
      ASSERT_TRUE(a.valid() && b.valid()) << "step " << k;
      touching += scratch.contacts > 0;
      limited += pair.moved > 0;
      ASSERT_FALSE(mass_inside(a.state(), b.state(), 0)) << "a mass of the first inside the second at step " << k;
      ASSERT_FALSE(mass_inside(b.state(), a.state(), 0)) << "a mass of the second inside the first at step " << k;
      double px, py;
      momentum(a.state(), b.state(), &px, &py);
      // Gravity adds g dt^2 to every mass's displacement each step.
      const double gravity_y = py0 + static_cast<double>(k) * n * p.gravity * dt * dt;
      worst_x = std::max(worst_x, std::abs(px - px0));
      worst_y = std::max(worst_y, std::abs(py - gravity_y));
    }
    EXPECT_GT(touching, 20) << "the rings never met";
    if (va > 10000) {
      EXPECT_GT(limited, 0) << "the limit never worked";
    }
    // Each ring's momentum changes by about 24 (va - vb) dt / 2 >= 0.2 in the collision; the
    // pair's stays to the rounding of positions of size 40 to 80 over 3000 steps, ~1e-11 (y, where
    // gravity's g dt^2 is added to each) and ~1e-13 (x).
    double pax = 0;
    for (int i = 0; i < a.state().size(); ++i) pax += a.state().x[i] - a.state().px[i];
    EXPECT_GT(std::abs(pax - a.state().size() * va * dt), 0.1) << "the collision did not change the first's momentum";
    EXPECT_LT(worst_x, 1e-11);
    EXPECT_LT(worst_y, 2e-10);
    // They met head on and parted.
    double ax, ay, bx, by;
    a.centre_of_mass(&ax, &ay);
    b.centre_of_mass(&bx, &by);
    EXPECT_GT(bx - ax, 2 * p.radius);
    std::cout << "  speeds " << va << ", " << vb << ": steps in contact " << touching << ", with the limit at work "
              << limited << "; largest change of the pair's momentum (displacement units): x " << worst_x << ", y "
              << worst_y << "\n";
  }
}

TEST(TwoDroplets, NoMassOfEitherRingIsEverInsideTheOtherInAMedium) {
  // The paper's cited case: phi = 0.79, non-overlapping grains. The second droplet is released
  // soon after the first (it catches up in the pores), and every step is checked.
  const Medium medium = test::small_medium_079();
  const DropletParams p;
  const SecondDroplet second = test::close_behind();
  const RunOptions o = test::long_enough();
  for (double x0 : {60.0, 100.0, 150.0}) {
    SCOPED_TRACE("x0 = " + std::to_string(x0));
    TwoDropletRun run(p, medium, x0, o, second);
    std::int64_t k = 0, both = 0, limited = 0;
    while (!run.finished()) {
      run.step();
      ++k;
      if (!run.first_running() || !run.second_running()) continue;
      ++both;
      limited += run.limited() > 0;
      const double s = periodic_shift(run.first().state(), run.second().state(), medium);
      ASSERT_FALSE(mass_inside(run.first().state(), run.second().state(), s)) << "step " << k;
      ASSERT_FALSE(mass_inside(run.second().state(), run.first().state(), -s)) << "step " << k;
    }
    const TwoDropletSummary sum = run.take();
    EXPECT_TRUE(sum.released);
    EXPECT_GT(both, 1000);
    EXPECT_NE(sum.first.outcome, Outcome::diverged) << sum.first.reason;
    EXPECT_NE(sum.second.outcome, Outcome::diverged) << sum.second.reason;
    std::cout << "  x0 " << x0 << ": " << to_string(sum.first.outcome) << " T " << sum.first.tortuosity << ", "
              << to_string(sum.second.outcome) << " T " << sum.second.tortuosity << ", steps in contact "
              << sum.contact_steps << " (the limit at work in " << limited << "), shared grains " << sum.shared_touched
              << "\n";
  }
}

TEST(TwoDroplets, DropletsThatNeverMeetRunAsEachWouldAlone) {
  // Released half a box apart, in separate columns of an empty box: neither ring comes within
  // reach of the other, so each run is its own, to the bit: the first from the start, the second
  // from its release (its steps counted from there).
  const Medium box = test::empty_medium(400, 300);
  const DropletParams p;
  SecondDroplet second;
  second.after = 60;
  second.offset_x = 200;
  RunOptions o;
  const TwoDropletSummary two = run_two_droplets(p, box, 100, o, second);
  const RunSummary first = Simulation(p, box).run(100, o), alone = Simulation(p, box).run(300, o);
  ASSERT_EQ(first.outcome, Outcome::passed);
  EXPECT_EQ(two.contact_steps, 0);
  EXPECT_TRUE(two.released);
  EXPECT_GT(two.released_at, 0);
  for (const auto& [pair, solo] : {std::pair{&two.first, &first}, std::pair{&two.second, &alone}}) {
    EXPECT_EQ(pair->outcome, solo->outcome);
    EXPECT_EQ(pair->steps, solo->steps);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(pair->tortuosity), std::bit_cast<std::uint64_t>(solo->tortuosity));
    EXPECT_EQ(pair->start_x, solo->start_x);
  }
  EXPECT_TRUE(std::isnan(two.first_held_at));
}

TEST(TwoDroplets, ASecondDropletReleasedByDistanceStartsWhenTheFirstIsThatFarDown) {
  const Medium box = test::empty_medium(400, 300);
  const DropletParams p;
  SecondDroplet second;
  second.after = 50;
  RunOptions o;
  o.path_interval = 1;
  const TwoDropletSummary two = run_two_droplets(p, box, 100, o, second);
  ASSERT_TRUE(two.released);
  // Free fall from rest: 50 = |g| t^2 / 2 at t = sqrt(100 / |g|), to a step.
  const double t = std::sqrt(2 * second.after / std::abs(p.gravity));
  EXPECT_NEAR(two.released_at, t, 1.5 * p.dt);
  // In an empty box the second follows the first's line, one behind the other, and never
  // catches up: both pass with T = 1.
  EXPECT_EQ(two.first.outcome, Outcome::passed);
  EXPECT_EQ(two.second.outcome, Outcome::passed);
  EXPECT_NEAR(two.second.tortuosity, 1.0, 1e-9);
  EXPECT_EQ(two.contact_steps, 0);

  second.release = SecondRelease::delay;
  second.after = 0.03;
  const TwoDropletSummary delayed = run_two_droplets(p, box, 100, o, second);
  ASSERT_TRUE(delayed.released);
  EXPECT_NEAR(delayed.released_at, 0.03, 1.5 * p.dt);
}

TEST(TwoDroplets, AFirstDropletAtRestIsHeldWhileTheSecondRuns) {
  // The V pocket holds a droplet (vibration_test.cpp). The first comes to rest in it, which
  // releases the second at once; the first is held, not ended, while the second moves, and ends
  // stuck after it. The second lands on it, rolls off, and falls past the V.
  const Medium pocket = test::v_pocket();
  const DropletParams p;
  SecondDroplet second;
  second.after = 1000;  // never by distance: the first's rest releases it
  RunOptions o;
  const RunSummary alone = Simulation(p, pocket).run(100, o);
  ASSERT_EQ(alone.outcome, Outcome::stuck);
  const TwoDropletSummary two = run_two_droplets(p, pocket, 100, o, second);
  ASSERT_TRUE(two.released);
  EXPECT_EQ(two.first.outcome, Outcome::stuck) << two.first.reason;
  EXPECT_EQ(two.second.outcome, Outcome::passed) << two.second.reason;
  EXPECT_FALSE(std::isnan(two.first_held_at));
  EXPECT_NEAR(two.released_at, two.first_held_at, 1.5 * p.dt);
  EXPECT_GT(two.first.steps, alone.steps);
  EXPECT_GT(two.contact_steps, 0);
  // The first ends after the second.
  EXPECT_GE(static_cast<double>(two.first.steps) * p.dt,
            two.released_at + static_cast<double>(two.second.steps) * p.dt);
}

TEST(TwoDroplets, OneShakenMediumShakesBothDropletsOnOneClock) {
  // The medium shakes from the first step; the second droplet, released later, feels it in the
  // same phase as the first at every step both run (the shaking's force on a mass is m a(t), t
  // the medium's time since it began to shake).
  const Medium medium = test::small_medium_079();
  DropletParams p;
  p.vibration_amplitude = 2;
  p.vibration_frequency = 100;
  p.vibration_start = VibrationStart::start;
  SecondDroplet second;
  second.after = 20;
  TwoDropletRun run(p, medium, 100, RunOptions{}, second);
  int both = 0;
  while (!run.finished()) {
    run.step();
    if (!run.first_running() || !run.second_running()) continue;
    const ShakeForce &a = run.first().runtime().shake, &b = run.second().runtime().shake;
    ASSERT_TRUE(a.on && b.on);
    ASSERT_EQ(a.fx, b.fx);
    ASSERT_EQ(a.fy, b.fy);
    ++both;
  }
  EXPECT_GT(both, 100);
  const TwoDropletSummary s = run.take();
  EXPECT_EQ(s.first.shaken_at, 0.0);
  EXPECT_EQ(s.second.shaken_at, 0.0);  // released into a medium already shaking
  // From rest: the first's rest starts the shaking, which then frees it or ends it stuck, and the
  // second is released into the shaking medium.
  p.vibration_start = VibrationStart::rest;
  second.after = 1000;  // released when the first's run ends
  const TwoDropletSummary rest = run_two_droplets(p, test::v_pocket(), 100, RunOptions{}, second);
  ASSERT_TRUE(rest.released);
  EXPECT_FALSE(std::isnan(rest.first.shaken_at));
  EXPECT_EQ(rest.second.shaken_at, 0.0);
}

TEST(TwoDroplets, ABatchOfPairsIsTheSameOnAnyThreadAndLaneCount) {
  // Each pair's run is its own, whoever steps it and beside whatever: one pair at a time on one
  // thread (lanes 2), six together in one block on one thread, and on four threads, the same bits,
  // in pair order.
  const Medium medium = test::small_medium_079();
  SecondDroplet second;
  second.after = 20;
  BatchOptions b;
  b.droplets = 6;
  b.seed = 11;
  b.threads = 1;
  b.lanes = 2;
  const std::vector<TwoDropletSummary> one = run_two_droplet_batch(DropletParams{}, medium, RunOptions{}, b, second);
  ASSERT_EQ(one.size(), 6U);
  for (const auto& [threads, lanes] : {std::pair{1, 0}, std::pair{4, 0}}) {
    SCOPED_TRACE(std::to_string(threads) + " threads, lanes " + std::to_string(lanes));
    b.threads = threads;
    b.lanes = lanes;
    const std::vector<TwoDropletSummary> other =
        run_two_droplet_batch(DropletParams{}, medium, RunOptions{}, b, second);
    ASSERT_EQ(other.size(), 6U);
    for (std::size_t i = 0; i < one.size(); ++i) {
      EXPECT_EQ(one[i].first.start_x, batch_start_x(b, medium, DropletParams{}, static_cast<int>(i)));
      EXPECT_EQ(one[i].first.steps, other[i].first.steps);
      EXPECT_EQ(one[i].second.steps, other[i].second.steps);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[i].first.tortuosity),
                std::bit_cast<std::uint64_t>(other[i].first.tortuosity));
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[i].second.tortuosity),
                std::bit_cast<std::uint64_t>(other[i].second.tortuosity));
      EXPECT_EQ(one[i].contact_steps, other[i].contact_steps);
    }
  }
}

TEST(TwoDroplets, ABadSecondDropletIsRefusedNamingIt) {
  const DropletParams p;
  const Medium box = test::empty_medium(400, 300);
  const auto refused = [&](SecondDroplet s, const std::string& words) {
    std::string why;
    EXPECT_FALSE(s.IsValid(p, &why));
    EXPECT_NE(why.find(words), std::string::npos) << why;
    try {
      run_two_droplets(p, box, 100, RunOptions{}, s);
      ADD_FAILURE() << "ran: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), why);
    }
  };
  SecondDroplet s;
  s.after = -1;
  refused(s, "second-after = -1: must be > 0");
  s.after = std::numeric_limits<double>::infinity();
  refused(s, "second-after = inf: must be > 0");
  s.after = 10;  // < 2 R + max_depth = 16.5
  refused(s, "second-after = 10: the second droplet would start overlapping the first");
  s.release = SecondRelease::delay;
  s.after = 1e-3;  // free fall covers 0.25
  refused(s, "second-after = 0.001: the second droplet would start overlapping the first");
  s.after = 1;
  s.offset_x = std::numeric_limits<double>::quiet_NaN();
  refused(s, "second-offset-x = nan: must be finite");
  // Starts far enough apart side by side need no delay.
  s.after = 1e-3;
  s.offset_x = 20;
  EXPECT_TRUE(s.IsValid(p, nullptr));
  EXPECT_THROW(parse_second_release("later"), std::invalid_argument);
  EXPECT_EQ(parse_second_release("delay"), SecondRelease::delay);
}

TEST(TwoDroplets, TheCommandLineRunsPairsAndRefusesABadSecondDropletInOneLine) {
  for (const auto& [args, message] :
       {std::pair{"--second-droplet later", "second-droplet"},
        {"--second-droplet distance --second-after 5", "second-after = 5: the second droplet would start overlapping"},
        {"--second-droplet delay --second-after nan", "second-after"},
        {"--second-after 60", "second-after, second-offset-x: have no effect without --second-droplet"},
        {"--second-droplet distance --walls --second-offset-x 30", "second-offset-x: between walls it needs --x0"}}) {
    const std::string runs = test::fresh_path("pairs_refused.csv");
    const test::Result r = test::run(std::string("simulate --porosity 0.9 --runs ") + runs + " " + args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(runs)) << args;
  }
  // Three pairs: a row per droplet, the pair's number and the droplet's order, and the same runs
  // as the library's (pair i from the batch's start i).
  const std::string runs = test::fresh_path("pairs.csv"), json = test::fresh_path("pairs.json");
  const test::Result r = test::run(
      "simulate --porosity 0.79 --kind non-overlapping --width 200 --height 200 "
      "--medium-seed 3 --droplets 3 --seed 5 --second-droplet distance --second-after 20 "
      "--quiet --runs " +
      runs + " --json " + json);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("pairs        3: 3 second droplets released"), std::string::npos) << r.out;
  std::ifstream in(runs);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header,
            "droplet,order,start_x,outcome,tortuosity,steps,touched,min_area_ratio,max_penetration,shaken_at,"
            "route_tortuosity,released_at,held_at,contact_steps,shared_touched");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 6);
  const Medium medium = test::small_medium_079();
  BatchOptions b;
  b.droplets = 3;
  b.seed = 5;
  SecondDroplet second;
  second.after = 20;
  const std::vector<TwoDropletSummary> pairs = run_two_droplet_batch(DropletParams{}, medium, RunOptions{}, b, second);
  ASSERT_EQ(pairs.size(), 3U);
  std::ifstream again(runs);
  std::getline(again, header);
  for (const TwoDropletSummary& p : pairs)
    for (const RunSummary* run : {&p.first, &p.second}) {
      ASSERT_TRUE(std::getline(again, line));
      // (appended, not "," + std::to_string(...): GCC 12 warns falsely of an overlapping copy there)
      EXPECT_NE(line.find(std::string(",").append(std::to_string(run->steps)).append(",")), std::string::npos) << line;
    }
}

}  // namespace
}  // namespace softdrop
