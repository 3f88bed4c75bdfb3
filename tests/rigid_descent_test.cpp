#include "media/rigid_descent.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

Medium box(std::vector<Grain> grains, bool periodic = true) {
  Medium m;
  m.width = 500, m.height = 500, m.periodic = periodic, m.grains = std::move(grains);
  return m;
}

std::string message(const Medium& m, double radius, double x0) {
  try {
    rigid_descent(m, radius, x0);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RigidDescent, AnEmptyBoxIsCrossedStraightDown) {
  const RigidDescent d = rigid_descent(box({}), 3.0, 123.25);
  EXPECT_TRUE(d.passed);
  EXPECT_EQ(d.tortuosity, 1.0);
  EXPECT_EQ(d.x, 123.25);
  EXPECT_EQ(d.y, 0.0);
  EXPECT_EQ(d.slides, 0);
}

TEST(RigidDescent, SlidesOverOneGrainToItsWidestPointThenFalls) {
  // A point lands 10 right of the top of a grain of radius 50 at (250, 250), slides to (300, 250)
  // and falls: the path is the drop to the grain, the arc and the last 250.
  const RigidDescent point = rigid_descent(box({{250, 250, 50}}), 0.0, 260.0);
  ASSERT_TRUE(point.passed);
  EXPECT_EQ(point.slides, 1);
  EXPECT_NEAR(point.x, 300.0, 1e-12);
  const double land = std::sqrt(50.0 * 50.0 - 10.0 * 10.0), arc = 50.0 * std::atan2(land, 10.0);
  EXPECT_NEAR(point.tortuosity, ((500 - 250 - land) + arc + 250) / 500, 1e-12);
  // A disc of radius 5 rolls on the grain dilated to 55 and leaves it 5 further out.
  const RigidDescent disc = rigid_descent(box({{250, 250, 50}}), 5.0, 240.0);
  ASSERT_TRUE(disc.passed);
  EXPECT_NEAR(disc.x, 195.0, 1e-12);
}

TEST(RigidDescent, StopsInTheNotchBetweenTwoOverlappingGrains) {
  // Grains of radius 50 at x = 200 and 280 meet at (240, 250 +- 30): the upper point is a dead end.
  const Medium m = box({{200, 250, 50}, {280, 250, 50}});
  const RigidDescent point = rigid_descent(m, 0.0, 230.0);
  EXPECT_FALSE(point.passed);
  EXPECT_TRUE(std::isnan(point.tortuosity));
  EXPECT_NEAR(point.x, 240.0, 1e-9);
  EXPECT_NEAR(point.y, 280.0, 1e-9);
  EXPECT_EQ(point.slides, 1);
  // From the right grain it slides into the same notch; outside both it slides off.
  EXPECT_NEAR(rigid_descent(m, 0.0, 262.0).y, 280.0, 1e-9);
  EXPECT_TRUE(rigid_descent(m, 0.0, 160.0).passed);
  // A disc of radius 20 rests higher: on the dilated circles' meeting point.
  const RigidDescent disc = rigid_descent(m, 20.0, 230.0);
  EXPECT_FALSE(disc.passed);
  EXPECT_NEAR(disc.y, 250 + std::sqrt(70.0 * 70.0 - 40.0 * 40.0), 1e-9);
}

TEST(RigidDescent, PassesAGapExactlyWhenItIsWiderThanTheDisc) {
  // Surfaces 10 apart: a disc of radius below 5 slides off the left grain and falls through.
  const Medium m = box({{200, 250, 50}, {310, 250, 50}});
  const RigidDescent narrow = rigid_descent(m, 4.9, 245.0);
  ASSERT_TRUE(narrow.passed);
  EXPECT_NEAR(narrow.x, 254.9, 1e-12);
  EXPECT_FALSE(rigid_descent(m, 5.1, 245.0).passed);
  EXPECT_TRUE(rigid_descent(m, 0.0, 255.0).passed);  // a point through the middle touches nothing
  EXPECT_EQ(rigid_descent(m, 0.0, 255.0).slides, 0);
}

TEST(RigidDescent, SlidesAcrossThePeriodicEdgeOrStopsAtAWall) {
  const Grain edge{490, 250, 50};
  const RigidDescent wrapped = rigid_descent(box({edge}), 0.0, 495.0);
  ASSERT_TRUE(wrapped.passed);
  EXPECT_NEAR(wrapped.x, 40.0, 1e-9);  // left the grain at 540, the periodic image of 40
  // With walls, the grain's upper half runs into the wall at x = 500: a dead end.
  const RigidDescent walled = rigid_descent(box({edge}, false), 0.0, 495.0);
  EXPECT_FALSE(walled.passed);
  EXPECT_NEAR(walled.x, 500.0, 1e-9);
  EXPECT_NEAR(walled.y, 250 + std::sqrt(50.0 * 50.0 - 10.0 * 10.0), 1e-9);
  // A disc of radius 20 keeps its centre 20 from the walls: the start is moved in.
  EXPECT_EQ(rigid_descent(box({}, false), 20.0, 3.0).x, 20.0);
}

TEST(RigidDescent, ItsPathIsAsLongAsItsTortuositySaysAndRunsOnAcrossThePeriodicEdge) {
  MediumOptions o;
  o.porosity = 0.7, o.seed = 9;
  const Medium m = generate_medium(o);
  int passed = 0;
  for (double x0 = 3; x0 < 500; x0 += 31) {
    const RigidDescent d = rigid_descent(m, 4.0, x0, true);
    const RigidDescent bare = rigid_descents(m, 4.0, {x0}).front();
    EXPECT_EQ(d.passed, bare.passed);
    EXPECT_EQ(d.x, bare.x);  // recording changes nothing
    EXPECT_EQ(d.y, bare.y);
    ASSERT_GE(d.path_x.size(), 2u);
    EXPECT_EQ(d.path_x.size(), d.path_y.size());
    EXPECT_EQ(d.path_x.front(), x0);
    EXPECT_EQ(d.path_y.back(), d.y);
    for (std::size_t i = 1; i < d.path_y.size(); ++i) EXPECT_LE(d.path_y[i], d.path_y[i - 1]);
    if (!d.passed) continue;
    ++passed;
    EXPECT_EQ(d.tortuosity, bare.tortuosity);
    // The path ends on y = 0; a droplet's runs on below it, as this one's, extended, does.
    std::vector<double> xs = d.path_x, ys = d.path_y;
    xs.push_back(xs.back()), ys.push_back(-1);
    // Arcs are drawn as chords 0.02 rad apart: about 2e-5 shorter.
    EXPECT_NEAR(polyline_tortuosity(xs, ys, m.height), d.tortuosity, 1e-4);
  }
  EXPECT_GT(passed, 5);
  const RigidDescent wrapped = rigid_descent(box({{490, 250, 50}}), 0.0, 495.0, true);
  EXPECT_NEAR(wrapped.path_x.back(), 540.0, 1e-9);  // the box's x is 40
  EXPECT_NEAR(wrapped.x, 40.0, 1e-9);
}

TEST(RigidDescent, APointPassesEveryNonOverlappingMedium) {
  // Grains that keep a gap never form a notch, so nothing stops a point; a disc wider than the
  // gaps stops somewhere at low porosity.
  MediumOptions o;
  o.kind = MediumKind::non_overlapping, o.porosity = 0.5;
  int stuck_wide = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    o.seed = seed;
    const Medium m = generate_medium(o);
    std::vector<double> starts;
    for (int i = 0; i < 50; ++i) starts.push_back(5.0 + 9.8 * i);
    for (const RigidDescent& d : rigid_descents(m, 0.0, starts)) {
      EXPECT_TRUE(d.passed);
      EXPECT_GE(d.tortuosity, 1.0);
    }
    for (const RigidDescent& d : rigid_descents(m, 8.0, starts)) {
      stuck_wide += !d.passed;
      if (!d.passed) {
        EXPECT_GT(d.y, 0.0);
      }
    }
  }
  EXPECT_GT(stuck_wide, 100);
}

TEST(RigidDescent, BadInputNamesTheParameter) {
  const Medium m = box({{250, 250, 50}});
  EXPECT_NE(message(m, -1.0, 10).find("radius = -1"), std::string::npos);
  EXPECT_NE(message(m, std::nan(""), 10).find("radius = nan"), std::string::npos);
  EXPECT_NE(message(m, 1.0, -1).find("x0 = -1"), std::string::npos);
  EXPECT_NE(message(m, 1.0, 501).find("x0 = 501"), std::string::npos);
  EXPECT_NE(message(box({}, false), 251.0, 10).find("radius = 251"), std::string::npos);
  EXPECT_EQ(message(m, 0.0, 500), "");
}

}  // namespace
}  // namespace softdrop
