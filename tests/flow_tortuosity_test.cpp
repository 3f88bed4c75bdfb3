// The creeping flow through a pore image against closed forms and published numbers: plane
// Poiseuille flow in straight slits (exact to second order), the length of slanted channels,
// Sangani and Acrivos's (1982) permeability of a square array of cylinders, and an empty box.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "pore_images.hpp"
#include "studies/pore_tortuosity.hpp"

namespace softdrop {
namespace {

// Channels at slope s (pore_images.hpp).
PoreImage channels(int n, double s, int period, int width, double pixel = 1) {
  return test::slanted_channels(n, s, period, width, pixel);
}

// One disc of solid fraction c at the centre of an n x n unit cell of side 1: periodic in both
// directions (buffer_rows = 0), the square array.
PoreImage unit_cell(int n, double c) {
  PoreImage im;
  im.nx = im.ny = n;
  im.pixel = 1.0 / n;
  im.pore.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 1);
  const double a = std::sqrt(c / std::numbers::pi);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) / n - 0.5, y = (j + 0.5) / n - 0.5;
      if (x * x + y * y < a * a) im.pore[static_cast<std::size_t>(i + n * j)] = 0;
    }
  return im;
}

FlowOptions periodic_in_y() {
  FlowOptions o;
  o.buffer_rows = 0;
  return o;
}

TEST(FlowTortuosity, StraightSlitsCarryPlanePoiseuilleFlowToSecondOrder) {
  // Slits w pixels wide, half the box open: k = phi w^2 / 12 in the continuum. The staggered grid
  // gives phi (w^2 + 2) / 12 exactly (its wall half a pixel from the last face), so the error falls
  // four times for each doubling of w.
  double previous = 0;
  for (const int w : {4, 8, 16, 32}) {
    SCOPED_TRACE(w);
    const HydrodynamicTortuosity f = hydrodynamic_tortuosity(channels(2 * w, 0, 2 * w, w, 0.5), periodic_in_y());
    const double exact = 0.5 * (w * 0.5) * (w * 0.5) / 12;  // pixel 0.5: k in length units squared
    EXPECT_NEAR(f.permeability, 0.5 * (w * w + 2) / 12.0 * 0.25, 1e-9 * exact);
    EXPECT_NEAR(f.tortuosity, 1.0, 1e-12);
    EXPECT_NEAR(f.porosity, 0.5, 1e-15);
    const double error = f.permeability / exact - 1;
    if (previous > 0) {
      EXPECT_NEAR(previous / error, 4.0, 1e-6);
    }
    previous = error;
  }
}

TEST(FlowTortuosity, SlantedChannelsGiveTheirLengthOverTheHeight) {
  // Channels at slope s: the flow runs along them, T = sqrt(1 + s^2), approached as the staircase
  // of their walls refines (45 degrees is exact on the grid).
  for (const double s : {1.0 / 3, 1.0}) {
    SCOPED_TRACE(s);
    const HydrodynamicTortuosity f = hydrodynamic_tortuosity(channels(240, s, 80, 20), periodic_in_y());
    EXPECT_NEAR(f.tortuosity, std::sqrt(1 + s * s), 3e-4 * std::sqrt(1 + s * s));
    EXPECT_LT(f.iterations, 20);
  }
  // Between buffers (the default) the image need not be periodic in y; the flow turns into the
  // channels within a few pixels of their ends, which costs a few tenths of a percent.
  const HydrodynamicTortuosity b = hydrodynamic_tortuosity(channels(240, 0.5, 80, 20));
  EXPECT_EQ(b.buffer_rows, 9);
  EXPECT_NEAR(b.tortuosity, std::sqrt(1.25), 0.004 * std::sqrt(1.25));
}

TEST(FlowTortuosity, ASquareArrayOfDiscsHasSanganiAndAcrivossPermeability) {
  // Sangani and Acrivos (1982), the square array's small-c expansion: k / a^2 = (-ln c - 1.476 +
  // 2 c - 1.774 c^2 + 4.078 c^3) / (8 c), a the discs' radius and c their solid fraction. At 256
  // pixels a cell the discs are 29 to 56 pixels in radius.
  for (const double c : {0.05, 0.1, 0.15}) {
    SCOPED_TRACE(c);
    const double reference = (-std::log(c) - 1.476 + 2 * c - 1.774 * c * c + 4.078 * c * c * c) / (8 * c);
    const HydrodynamicTortuosity f = hydrodynamic_tortuosity(unit_cell(256, c), periodic_in_y());
    const double a2 = c / std::numbers::pi;
    EXPECT_NEAR(f.permeability / a2, reference, 0.02 * reference);
    EXPECT_GT(f.tortuosity, 1.01);  // the flow bends round the discs
    EXPECT_LT(f.tortuosity, 1.02);
  }
}

TEST(FlowTortuosity, AnEmptyBoxGivesOneAndWallsGivePoiseuille) {
  PoreImage open;
  open.nx = open.ny = 40;
  open.pore.assign(1600, 1);
  const HydrodynamicTortuosity free = hydrodynamic_tortuosity(open);
  EXPECT_EQ(free.tortuosity, 1.0);
  EXPECT_EQ(free.permeability, std::numeric_limits<double>::infinity());  // nothing holds the flow
  open.periodic = false;  // walls at x = 0 and W: Poiseuille between them, k = W^2 / 12
  const HydrodynamicTortuosity walls = hydrodynamic_tortuosity(open);
  EXPECT_NEAR(walls.tortuosity, 1.0, 1e-9);
  EXPECT_NEAR(walls.permeability, (40.0 * 40 + 2) / 12, 1e-6);
}

TEST(FlowTortuosity, NoPathOrBadOptionsAreRefusedByName) {
  PoreImage blocked = channels(40, 0, 40, 40);
  for (int i = 0; i < 40; ++i) blocked.pore[static_cast<std::size_t>(i + 40 * 20)] = 0;  // a solid row
  try {
    (void)hydrodynamic_tortuosity(blocked);
    ADD_FAILURE() << "a blocked image was solved";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "image: no pore path from the top to the bottom");
  }
  FlowOptions bad;
  bad.tolerance = 0;
  EXPECT_THROW((void)hydrodynamic_tortuosity(channels(40, 0, 20, 10), bad), std::invalid_argument);
  bad = FlowOptions{};
  bad.buffer_rows = -2;
  EXPECT_THROW((void)hydrodynamic_tortuosity(channels(40, 0, 20, 10), bad), std::invalid_argument);
  bad = FlowOptions{};
  bad.max_iterations = 1;  // a bent flow needs more than one
  EXPECT_THROW((void)hydrodynamic_tortuosity(channels(120, 1.0 / 3, 40, 10), bad), std::runtime_error);
}

TEST(FlowTortuosity, TheFieldsHoldTheFlowAndAreTheSameBitsEveryTime) {
  const PoreImage im = channels(160, 0.5, 40, 10);  // x = y / 2 + const along a channel, periodic in y
  const HydrodynamicTortuosity a = hydrodynamic_tortuosity(im, periodic_in_y()),
                               b = hydrodynamic_tortuosity(im, periodic_in_y());
  EXPECT_EQ(a.tortuosity, b.tortuosity);
  EXPECT_EQ(a.permeability, b.permeability);
  ASSERT_EQ(a.uy.size(), im.pore.size());
  double down = 0, across = 0;
  for (std::size_t k = 0; k < im.pore.size(); ++k) {
    EXPECT_EQ(std::isnan(a.uy[k]), im.pore[k] == 0);
    if (std::isnan(a.uy[k])) continue;
    EXPECT_EQ(a.uy[k], b.uy[k]);
    EXPECT_EQ(a.ux[k], b.ux[k]);
    down -= a.uy[k], across -= a.ux[k];
  }
  // The mean flow runs along the channels, down and to the left, and is the superficial velocity.
  EXPECT_NEAR(across / down, 0.5, 0.005);
  EXPECT_NEAR(down / static_cast<double>(im.pore.size()), a.superficial_velocity, 1e-12 * a.superficial_velocity);
}

}  // namespace
}  // namespace softdrop
