// The pore-space tortuosities against closed forms: an empty box gives 1; straight vertical
// channels give a diffusive tau of 1 whatever their porosity; a square array of discs gives
// Rayleigh's (1892) effective diffusivity; slanted channels give the straight path's length. Both
// converge at first order in the pixel size, so the value extrapolated from a resolution and its
// double (2 T(2n) - T(n), Richardson) is within a few tenths of a percent.
#include "studies/pore_tortuosity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

#include "pore_images.hpp"

namespace softdrop {
namespace {

using test::slanted_channels;

// 2 x 2 cells of side 100, a disc of solid fraction f in each (periodic in x): the lines between
// rows of discs are equipotentials by symmetry, so the Dirichlet edges cut the infinite array.
Medium square_array(double f) {
  Medium m;
  m.width = m.height = 200;
  const double r = 100 * std::sqrt(f / std::numbers::pi);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) m.grains.push_back({(i + 0.5) * 100, (j + 0.5) * 100, r});
  return m;
}

TEST(PoreTortuosity, AnEmptyBoxGivesOneForEveryDefinition) {
  for (const bool periodic : {true, false}) {
    Medium empty;
    empty.periodic = periodic;
    const PoreImage im = pore_image(empty, 64);
    EXPECT_EQ(im.porosity(), 1.0);
    const GeometricTortuosity g = geometric_tortuosity(im);
    EXPECT_NEAR(g.tortuosity, 1.0, 1e-12);
    EXPECT_EQ(g.connected, 64);
    EXPECT_NEAR(diffusive_tortuosity(im).tau, 1.0, 1e-9);
  }
}

TEST(PoreTortuosity, StraightChannelsDiffuseWithTauOneWhateverTheirPorosity) {
  const PoreImage im = slanted_channels(120, 0, 40, 10);  // a quarter of the box open, in straight columns
  const DiffusiveTortuosity d = diffusive_tortuosity(im);
  EXPECT_NEAR(d.porosity, 0.25, 1e-12);
  EXPECT_NEAR(d.effective_diffusivity, 0.25, 1e-9);
  EXPECT_NEAR(d.tau, 1.0, 1e-9);
  EXPECT_NEAR(geometric_tortuosity(im).tortuosity, 1.0, 1e-12);
}

TEST(PoreTortuosity, ASquareArrayOfDiscsDiffusesAsRayleighFound) {
  for (const double f : {0.3, 0.5}) {
    SCOPED_TRACE(f);
    const Medium m = square_array(f);
    // Rayleigh (1892), insulating cylinders in a square array, the gradient along a side.
    const double d_eff = 1 - 2 * f / (1 + f - 0.305827 * std::pow(f, 4) - 0.013362 * std::pow(f, 8));
    const double tau = (1 - f) / d_eff;
    const double coarse = diffusive_tortuosity(pore_image(m, 200)).tau;
    const double fine = diffusive_tortuosity(pore_image(m, 400)).tau;
    EXPECT_NEAR(fine, tau, 0.01 * tau);                       // 1 % at 100 pixels a radius of 0.5's disc
    EXPECT_LT(std::abs(fine - tau), std::abs(coarse - tau));  // and closer at the finer pixels
    EXPECT_NEAR(2 * fine - coarse, tau, 0.002 * tau);         // extrapolated: 0.2 %
  }
}

TEST(PoreTortuosity, SlantedChannelsGiveTheStraightPathThroughThem) {
  // Channels of slope 1/2 (x against y), a tenth of the box wide. From a start u into the channel
  // the shortest path runs straight to the channel's far edge at the bottom: horizontal run
  // H s + u - w over the height H.
  auto continuum = [](double n) {
    const double h = n, s = 0.5, w = n / 10;
    double sum = 0;
    const int m = 100000;
    for (int k = 0; k < m; ++k) {
      const double u = (k + 0.5) / m * w, run = std::max(0.0, h * s + u - w);
      sum += std::sqrt(h * h + run * run) / h;
    }
    return sum / m;
  };
  const double coarse = geometric_tortuosity(slanted_channels(200, 0.5, 100, 20)).tortuosity;
  const double fine = geometric_tortuosity(slanted_channels(400, 0.5, 200, 40)).tortuosity;
  const double exact = continuum(400);
  EXPECT_NEAR(fine, exact, 0.01 * exact);
  EXPECT_NEAR(2 * fine - coarse, exact, 0.001 * exact);
  // The diffusive tau of long channels is 1 / cos^2 = 1 + s^2, less their ends' share (the limit
  // of these is 1.237): within 2 % at this size.
  EXPECT_NEAR(diffusive_tortuosity(slanted_channels(400, 0.5, 200, 40)).tau, 1.25, 0.02 * 1.25);
}

// Traced down the distance field: straight down an empty box; through slanted channels, from the
// top edge to the bottom edge, never through solid, and as long as the channel makes it.
TEST(PoreTortuosity, ShortestPathsRunFromTheTopEdgeToTheBottomThroughPores) {
  Medium empty;
  const PoreImage open = pore_image(empty, 50);
  const auto straight = shortest_paths(open, geometric_tortuosity(open), 5);
  ASSERT_EQ(straight.size(), 5u);
  for (const PorePath& p : straight) {
    EXPECT_EQ(p.y.front(), 500.0);
    EXPECT_EQ(p.y.back(), 0.0);
    for (double x : p.x) EXPECT_EQ(x, p.x.front());
  }
  const PoreImage im = slanted_channels(200, 0.5, 100, 20);
  const GeometricTortuosity g = geometric_tortuosity(im);
  for (const PorePath& p : shortest_paths(im, g, 8)) {
    double length = 0;
    for (std::size_t k = 1; k < p.x.size(); ++k) {
      length += std::hypot(p.x[k] - p.x[k - 1], p.y[k] - p.y[k - 1]);
      if (k + 1 < p.x.size()) {  // the points between the edges are pore pixels' centres
        const int i = static_cast<int>(std::floor(p.x[k])) % 200, j = static_cast<int>(std::floor(p.y[k]));
        EXPECT_TRUE(im.pore[static_cast<std::size_t>((i + 200) % 200 + 200 * j)]);
      }
    }
    // Eight directions make the drawn path a little longer than the distance field's, never shorter.
    EXPECT_GE(length / 200, g.shortest * 0.999);
    EXPECT_LE(length / 200, g.longest * 1.09);
  }
}

TEST(PoreTortuosity, NoPathFromTopToBottomIsSaidNotGivenAsANumber) {
  PoreImage im = slanted_channels(40, 0, 10, 5);
  for (int i = 0; i < 40; ++i) im.pore[static_cast<std::size_t>(i + 40 * 20)] = 0;  // a solid row across
  for (const auto& call : {std::function<void()>([&] { geometric_tortuosity(im); }),
                           std::function<void()>([&] { diffusive_tortuosity(im); })}) {
    try {
      call();
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "image: no pore path from the top to the bottom");
    }
  }
  EXPECT_THROW(pore_image(Medium{}, 1), std::invalid_argument);
  PoreImage bad = im;
  bad.pixel = std::nan("");
  EXPECT_THROW(geometric_tortuosity(bad), std::invalid_argument);
}

}  // namespace
}  // namespace softdrop
