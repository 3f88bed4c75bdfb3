#include "media/grain_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop {
namespace {

Medium overlapping(bool periodic, std::uint64_t seed) {
  MediumOptions o;
  o.porosity = 0.7;
  o.width = o.height = 400;
  o.periodic = periodic;
  o.seed = seed;
  return generate_medium(o);
}

// Stored disc k's surface from (x, y): negative inside.
double surface_distance(const GrainGrid& grid, std::size_t k, double x, double y) {
  return std::hypot(x - grid.gx()[k], y - grid.gy()[k]) - grid.gr()[k];
}

// What the simulator's anchor balls rely on: a disc that is not listed in a point's cell is at
// least edge_distance() from the point, halo or not, inside the grid and around it.
TEST(GrainGrid, NoUnlistedDiscIsNearerThanTheEdgeDistance) {
  for (const bool periodic : {false, true}) {
    const Medium m = overlapping(periodic, 3);
    for (const double halo : {0.0, 0.25, 0.5, 1.0}) {
      SCOPED_TRACE(testing::Message() << "periodic " << periodic << ", halo " << halo);
      const GrainGrid grid(m, 0, halo);
      EXPECT_DOUBLE_EQ(grid.halo(), halo * grid.cell_size());
      std::mt19937_64 rng(11);
      // Periodic queries take x wrapped into [0, W); walled ones may be anywhere, also off the grid.
      std::uniform_real_distribution<double> ux(periodic ? 0.0 : -60.0, periodic ? m.width : m.width + 60.0),
          uy(-60.0, m.height + 60.0);
      int listed_near = 0;
      for (int p = 0; p < 3000; ++p) {
        const double x = std::min(ux(rng), std::nextafter(m.width, 0.0)), y = uy(rng);
        const auto range = grid.query(x, y);
        const double reach = grid.edge_distance(x, y);
        ASSERT_GE(reach, 0.0);
        for (std::size_t k = 0; k < grid.gx().size(); ++k) {
          const bool listed = std::find(range.begin, range.end, static_cast<std::int32_t>(k)) != range.end;
          if (listed) {
            ++listed_near;
          } else {
            ASSERT_GE(surface_distance(grid, k, x, y), reach * (1 - 1e-12)) << "disc " << k << " at " << x << ", " << y;
          }
        }
      }
      EXPECT_GT(listed_near, 3000);  // the points do have discs near them
    }
  }
}

TEST(GrainGrid, TheHaloAddsItsLengthToTheEdgeDistanceInsideTheGrid) {
  const Medium m = overlapping(false, 4);
  const GrainGrid plain(m), wide(m, 0, 0.5);
  ASSERT_EQ(plain.cell_size(), wide.cell_size());
  EXPECT_GT(wide.entries(), plain.entries());
  EXPECT_GE(wide.max_cell_entries(), plain.max_cell_entries());
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0, 400);
  for (int p = 0; p < 1000; ++p) {
    const double x = u(rng), y = u(rng);
    EXPECT_DOUBLE_EQ(wide.edge_distance(x, y), plain.edge_distance(x, y) + 0.5 * plain.cell_size());
  }
  // Off the grid the grid itself is the bound, with or without a halo; NaN stays NaN.
  EXPECT_EQ(wide.edge_distance(-1e4, 200), plain.edge_distance(-1e4, 200));
  EXPECT_TRUE(std::isnan(wide.edge_distance(std::nan(""), 200)));
  EXPECT_TRUE(std::isnan(wide.edge_distance(200, std::nan(""))));
}

// The contact forces of a mass inside several discs are summed in list order, so that order must
// not depend on the grid: every cell lists its discs in increasing order, and the discs holding a
// point come in the same order whatever the cell size or halo.
TEST(GrainGrid, TheDiscsHoldingAPointComeInTheSameOrderWhateverTheCellAndHalo) {
  const Medium m = overlapping(true, 5);
  const GrainGrid a(m), b(m, 0, 0.5), c(m, 7.5, 1.0);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0, 400);
  const auto holding = [](const GrainGrid& g, double x, double y) {
    std::vector<std::int32_t> in;
    const auto range = g.query(x, y);
    EXPECT_TRUE(std::is_sorted(range.begin, range.end));
    for (const std::int32_t* k = range.begin; k != range.end; ++k)
      if (surface_distance(g, static_cast<std::size_t>(*k), x, y) < 0) in.push_back(*k);
    return in;
  };
  int multiple = 0;
  for (int p = 0; p < 5000; ++p) {
    const double x = std::min(u(rng), std::nextafter(400.0, 0.0)), y = u(rng);
    const auto in = holding(a, x, y);
    multiple += in.size() > 1;
    ASSERT_EQ(in, holding(b, x, y)) << x << ", " << y;
    ASSERT_EQ(in, holding(c, x, y)) << x << ", " << y;
  }
  EXPECT_GT(multiple, 50);  // overlapping grains: points inside two or more discs are tested
}

TEST(GrainGrid, ANegativeOrHugeHaloIsRefused) {
  const Medium m = overlapping(false, 6);
  for (const double halo : {-0.5, 17.0, std::nan("")}) {
    try {
      const GrainGrid grid(m, 0, halo);
      ADD_FAILURE() << halo;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("halo"), std::string::npos) << e.what();
    }
  }
}

TEST(GrainGrid, FewLargeGrainsAmongManySmallKeepTheGridLinearAndExact) {
  // 20 000 small grains set the cell size; 150 grains 800 times wider would each cover
  // ~10^5 cells of that size (1.5e7 entries). The grid coarsens instead, and stays exact, with the
  // simulator's halo too.
  Medium m{2000, 2000, false, {}, nullptr};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 2000);
  for (int i = 0; i < 20000; ++i) m.grains.push_back({u(rng), u(rng), 0.5});
  for (int i = 0; i < 150; ++i) m.grains.push_back({u(rng), u(rng), 400});
  for (const double halo : {0.0, 0.5}) {
    const GrainGrid grid(m, 0, halo);
    EXPECT_LE(grid.entries(), 64 * m.grains.size() + 4096);
    for (int k = 0; k < 2000; ++k) {  // every disc holding a point is listed in the point's cell
      const double x = u(rng), y = u(rng);
      const auto range = grid.query(x, y);
      for (std::size_t i = 0; i < m.grains.size(); ++i) {
        const auto& g = m.grains[i];
        if ((x - g.x) * (x - g.x) + (y - g.y) * (y - g.y) < g.r * g.r) {
          ASSERT_NE(std::find(range.begin, range.end, static_cast<std::int32_t>(i)), range.end) << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace softdrop
