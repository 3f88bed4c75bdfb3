// The shaken medium (DropletParams::vibration_*): the droplet feels the medium's inertial force in
// its frame, starts to feel it when it first comes to rest, and is freed from a pocket that holds
// it without shaking. That every layout of the step gives a shaken droplet its solo bits is
// interleaved_test.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>

#include "cli_run.hpp"
#include "fixtures.hpp"
#include "softdrop/simulation.hpp"
#include "studies/area_trace.hpp"

namespace softdrop {
namespace {

DropletParams shaken(double amplitude, double frequency, VibrationAxis axis, VibrationStart start) {
  DropletParams p;
  p.vibration_amplitude = amplitude;
  p.vibration_frequency = frequency;
  p.vibration_axis = axis;
  p.vibration_start = start;
  return p;
}

TEST(Vibration, AFreeDropletMovesAgainstTheShakenMedium) {
  // No grains and no gravity: the droplet stays where it is while the medium moves by
  // A (1 - cos 2 pi f t), so in the medium's frame its centre moves by -A (1 - cos 2 pi f t), on
  // each axis the medium shakes along. Position Verlet from rest is off by about dt A (2 pi f)^2 / 2
  // a time unit, 1 % of A over the period checked here.
  const Medium box = test::empty_medium();
  const double A = 3, f = 100;
  for (VibrationAxis axis : {VibrationAxis::x, VibrationAxis::y, VibrationAxis::xy}) {
    SCOPED_TRACE(to_string(axis));
    DropletParams p = shaken(A, f, axis, VibrationStart::start);
    p.gravity = 0;
    RunOptions o;
    o.path_interval = 1;
    o.max_steps = static_cast<std::int64_t>(std::llround(1.25 / (f * p.dt)));  // a period and a quarter
    o.rest_window = 0;
    const RunSummary s = Simulation(p, box).run(250, o);
    ASSERT_EQ(s.outcome, Outcome::timeout) << s.reason;
    EXPECT_EQ(s.shaken_at, 0.0);
    double worst = 0, farthest = 0;
    for (std::size_t k = 0; k < s.path_t.size(); ++k) {
      const double expected = -A * (1 - std::cos(2 * M_PI * f * s.path_t[k]));
      const double dx = s.path_x[k] - s.path_x[0], dy = s.path_y[k] - s.path_y[0];
      worst = std::max(worst, std::abs((axis == VibrationAxis::y ? 0.0 : expected) - dx));
      worst = std::max(worst, std::abs((axis == VibrationAxis::x ? 0.0 : expected) - dy));
      farthest = std::max(farthest, std::max(std::abs(dx), std::abs(dy)));
    }
    EXPECT_LT(worst, 0.015 * A);
    EXPECT_NEAR(farthest, 2 * A, 0.03 * A);  // half a period in: the medium 2 A away
  }
}

TEST(Vibration, WithoutAmplitudeNothingShakes) {
  // A frequency, axis and start with no amplitude are the defaults' run to the bit.
  const Medium pocket = test::v_pocket();
  DropletParams p = shaken(0, 300, VibrationAxis::xy, VibrationStart::start);
  Simulation a(DropletParams{}, pocket), b(p, pocket);
  const RunSummary ra = a.run(100, RunOptions{}), rb = b.run(100, RunOptions{});
  EXPECT_EQ(ra.steps, rb.steps);
  EXPECT_EQ(a.state_hash(), b.state_hash());
  EXPECT_TRUE(std::isnan(rb.shaken_at));
  // Beside the V, a droplet falls past a grain: never shaken, its route is its path.
  const RunSummary past = Simulation(p, pocket).run(30, RunOptions{});
  ASSERT_EQ(past.outcome, Outcome::passed) << past.reason;
  EXPECT_EQ(past.route_tortuosity, past.tortuosity);
}

TEST(Vibration, ADropletAtRestInAPocketIsShakenFree) {
  // Two overlapping grains make a closed V. Dropped into it, the droplet comes to rest and is
  // stuck. Shaken sideways from then on, it climbs out over a grain and falls free. The shaking
  // begins at the step the unshaken run found it at rest: until then the two runs are one.
  const Medium pocket = test::v_pocket();
  const RunSummary still = Simulation(DropletParams{}, pocket).run(100, RunOptions{});
  ASSERT_EQ(still.outcome, Outcome::stuck) << still.reason;
  EXPECT_NE(still.reason.find("at rest"), std::string::npos) << still.reason;
  const DropletParams p = shaken(test::kVPocketAmplitude, 100, VibrationAxis::x, VibrationStart::rest);
  const RunSummary freed = Simulation(p, pocket).run(100, RunOptions{});
  EXPECT_EQ(freed.outcome, Outcome::passed) << freed.reason;
  EXPECT_EQ(freed.shaken_at, static_cast<double>(still.steps) * p.dt);
  EXPECT_GT(freed.tortuosity, 1.0);
  // Its route, the path once a shaking period, is shorter than the path with the shaking in it.
  EXPECT_GT(freed.route_tortuosity, 1.0);
  EXPECT_LT(freed.route_tortuosity, freed.tortuosity);
  // A tenth of that amplitude leaves it in the pocket: stuck by the stuck test, shaking.
  const RunSummary weak =
      Simulation(shaken(test::kVPocketAmplitude / 10, 100, VibrationAxis::x, VibrationStart::rest), pocket)
          .run(100, RunOptions{});
  EXPECT_EQ(weak.outcome, Outcome::stuck) << weak.reason;
  EXPECT_NE(weak.reason.find("while the medium shook"), std::string::npos) << weak.reason;
  EXPECT_FALSE(std::isnan(weak.shaken_at));
}

TEST(Vibration, TheAreaTraceReplaysTheShakenRun) {
  // The trace replays the run step by step. Shaken as the run was, the replayed droplet leaves the
  // pocket, and its highest mass leaves the medium after its centre did in the run; unshaken, it
  // would still be in the pocket.
  const Medium pocket = test::v_pocket();
  const DropletParams p = shaken(test::kVPocketAmplitude, 100, VibrationAxis::x, VibrationStart::rest);
  const RunSummary run = Simulation(p, pocket).run(100, RunOptions{});
  const AreaTrace trace = trace_area(p, pocket, 100, RunOptions{}, 50);
  ASSERT_EQ(run.outcome, Outcome::passed);
  EXPECT_EQ(trace.run.steps, run.steps);
  ASSERT_FALSE(std::isnan(trace.leave));
  EXPECT_GT(trace.leave, static_cast<double>(run.steps) * p.dt);
  EXPECT_LT(trace.leave, static_cast<double>(run.steps) * p.dt + 0.01);
}

TEST(Vibration, BadValuesAreRefusedByName) {
  std::string why;
  EXPECT_FALSE(shaken(-1, 100, VibrationAxis::x, VibrationStart::rest).IsValid(&why));
  EXPECT_EQ(why, "vibration-amplitude = -1: must be >= 0");
  EXPECT_FALSE(
      shaken(1, std::numeric_limits<double>::infinity(), VibrationAxis::x, VibrationStart::rest).IsValid(&why));
  EXPECT_EQ(why, "vibration-frequency = inf: must be >= 0");
  EXPECT_FALSE(shaken(1, std::nan(""), VibrationAxis::x, VibrationStart::rest).IsValid(&why));
  EXPECT_EQ(why.rfind("vibration-frequency = ", 0), 0u) << why;
  EXPECT_FALSE(shaken(1, 0, VibrationAxis::x, VibrationStart::rest).IsValid(&why));
  EXPECT_EQ(why, "vibration-frequency = 0: must be > 0 when vibration-amplitude = 1 shakes the medium");
  // 1e4 at dt = 6e-6: 16.7 steps a period.
  EXPECT_FALSE(shaken(1, 1e4, VibrationAxis::x, VibrationStart::rest).IsValid(&why));
  EXPECT_EQ(why.rfind("vibration-frequency = 10000, dt = 6e-06: a period of 16.6", 0), 0u) << why;
  EXPECT_TRUE(shaken(1, 8e3, VibrationAxis::x, VibrationStart::rest).IsValid(&why)) << why;
  VibrationAxis axis;
  EXPECT_THROW(parse_name("z", &axis), std::invalid_argument);
  parse_name("xy", &axis);
  EXPECT_EQ(axis, VibrationAxis::xy);
}

TEST(Vibration, TheCommandLineRefusesBadShakingInOneLineAndStoresGoodShakingWithTheSweep) {
  for (const auto& [args, message] :
       {std::pair{"--vibration-amplitude -1", "vibration-amplitude = -1: must be >= 0"},
        {"--vibration-amplitude 1 --vibration-frequency inf", "vibration-frequency = inf: must be >= 0"},
        {"--vibration-amplitude 1", "vibration-frequency = 0: must be > 0 when vibration-amplitude = 1"},
        {"--vibration-axis z", "--vibration-axis: z not in {x,y,xy}"}}) {
    const std::string db = test::fresh_path("vibration_refused.db");
    const test::Result r =
        test::run(std::string("sweep --porosities 0.8 --media 1 --droplets 1 --quiet --db ") + db + " " + args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(db)) << args;
  }
  // Stored with the sweep: the same command resumes it, another amplitude is another sweep.
  const std::string db = test::fresh_path("vibration_sweep.db");
  const std::string sweep = "sweep --porosities 0.8 --media 1 --droplets 2 --vibration-frequency 100 --db " + db;
  ASSERT_EQ(test::run(sweep + " --vibration-amplitude 2 --quiet").code, 0);
  const test::Result again = test::run(sweep + " --vibration-amplitude 2");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("sweep 1: 1 of 1 media stored; this session 0 media"), std::string::npos) << again.err;
  const test::Result other = test::run(sweep + " --vibration-amplitude 3");
  ASSERT_EQ(other.code, 0) << other.err;
  EXPECT_NE(other.err.find("differs in: vibration-amplitude 2.0 -> 3.0"), std::string::npos) << other.err;
  EXPECT_NE(other.err.find("sweep 2: 1 of 1 media stored; this session 1 media"), std::string::npos) << other.err;
}

}  // namespace
}  // namespace softdrop
