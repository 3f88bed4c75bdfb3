#include "grain_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace softdrop {

GrainGrid::GrainGrid(const Medium& medium, double cell_size, double halo_cells) {
  if (!(halo_cells >= 0 && halo_cells <= 16))
    throw std::invalid_argument("grain grid halo " + std::to_string(halo_cells) + " cells is not in [0, 16]");
  const int n = static_cast<int>(medium.grains.size());
  for (int i = 0; i < n; ++i) {
    const Grain& g = medium.grains[static_cast<std::size_t>(i)];
    auto add = [&](double x) {
      gx_.push_back(x);
      gy_.push_back(g.y);
      gr_.push_back(g.r);
      id_.push_back(i);
    };
    add(g.x);
    if (medium.periodic) {
      // Images of grains that cross the seam, so a query in [0, W) sees everything.
      if (g.x - g.r < 0) add(g.x + medium.width);
      if (g.x + g.r > medium.width) add(g.x - medium.width);
    }
  }
  if (cell_size <= 0) {
    double sum = 0;
    for (double r : gr_) sum += 2 * r;
    cell_size = gr_.empty() ? medium.width : sum / static_cast<double>(gr_.size());
  }
  double xmin = 0, xmax = medium.width, ymin = 0, ymax = medium.height;
  for (std::size_t k = 0; k < gx_.size(); ++k) {
    xmin = std::min(xmin, gx_[k] - gr_[k]);
    xmax = std::max(xmax, gx_[k] + gr_[k]);
    ymin = std::min(ymin, gy_[k] - gr_[k]);
    ymax = std::max(ymax, gy_[k] + gr_[k]);
  }
  // Keep the cell count bounded (a few per grain) even for a huge empty box.
  const double area = (xmax - xmin) * (ymax - ymin);
  const double max_cells = 4.0 * static_cast<double>(gx_.size()) + 1024.0;
  if (area / (cell_size * cell_size) > max_cells) cell_size = std::sqrt(area / max_cells);
  x0_ = xmin;
  y0_ = ymin;
  // Cell index of a coordinate, clamped in floating point first so that no cast can overflow.
  auto cell_of = [&](double offset, int cells_along) {
    const double c = std::floor(offset * inv_cell_);
    if (!(c > 0)) return 0;  // also NaN, from an infinite extent
    return c >= cells_along - 1 ? cells_along - 1 : static_cast<int>(c);
  };
  // The cells a disc's bounding box, grown by the halo, overlaps.
  auto cell_span = [&](std::size_t k, int* ix0, int* ix1, int* iy0, int* iy1) {
    const double r = gr_[k] + halo_;
    *ix0 = cell_of(gx_[k] - r - x0_, nx_);
    *ix1 = cell_of(gx_[k] + r - x0_, nx_);
    *iy0 = cell_of(gy_[k] - r - y0_, ny_);
    *iy1 = cell_of(gy_[k] + r - y0_, ny_);
  };
  // A few large grains among many small ones would cover many cells each; grow the cells until
  // the grid holds at most a bounded number of entries per grain, so memory stays linear. The
  // per-cell counts are made in the same pass; a grain's span is checked against the bound
  // before its cells are counted, so no pass does more than max_entries work.
  const double max_entries = 64.0 * static_cast<double>(gx_.size()) + 4096.0;
  std::int64_t cells = 0;
  for (;;) {
    inv_cell_ = 1.0 / cell_size;
    halo_ = halo_cells * cell_size;
    nx_ = static_cast<int>(std::clamp(std::ceil((xmax - xmin) * inv_cell_), 1.0, max_cells));
    ny_ = static_cast<int>(std::clamp(std::ceil((ymax - ymin) * inv_cell_), 1.0, max_cells));
    cells = static_cast<std::int64_t>(nx_) * ny_;
    start_.assign(static_cast<std::size_t>(cells + 1), 0);
    const bool one_cell = nx_ == 1 && ny_ == 1;
    double entries = 0;
    bool fits = true;
    for (std::size_t k = 0; k < gx_.size(); ++k) {
      int ix0, ix1, iy0, iy1;
      cell_span(k, &ix0, &ix1, &iy0, &iy1);
      entries += static_cast<double>(ix1 - ix0 + 1) * static_cast<double>(iy1 - iy0 + 1);
      if (entries > max_entries && !one_cell) {
        fits = false;
        break;
      }
      for (int iy = iy0; iy <= iy1; ++iy)
        for (int ix = ix0; ix <= ix1; ++ix) ++start_[static_cast<std::size_t>(iy) * nx_ + ix + 1];
    }
    if (fits) break;
    cell_size *= 2;
  }
  for (std::int64_t c = 0; c < cells; ++c) {
    max_cell_ = std::max(max_cell_, static_cast<std::size_t>(start_[c + 1]));
    start_[c + 1] += start_[c];
  }
  items_.resize(static_cast<std::size_t>(start_[cells]));
  std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < gx_.size(); ++k) {
    int ix0, ix1, iy0, iy1;
    cell_span(k, &ix0, &ix1, &iy0, &iy1);
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix)
        items_[static_cast<std::size_t>(fill[static_cast<std::size_t>(iy) * nx_ + ix]++)] =
            static_cast<std::int32_t>(k);
  }
  discs_.reserve(items_.size());
  for (const std::int32_t k : items_) {
    const auto u = static_cast<std::size_t>(k);
    discs_.push_back({gx_[u], gy_[u], gr_[u], id_[u]});
  }
}

double GrainGrid::edge_distance(double x, double y) const {
  const double fx = (x - x0_) * inv_cell_, fy = (y - y0_) * inv_cell_;
  if (fx >= 0 && fy >= 0 && fx < nx_ && fy < ny_) {
    const double ix = std::floor(fx), iy = std::floor(fy);
    return std::min(std::min(fx - ix, ix + 1 - fx), std::min(fy - iy, iy + 1 - fy)) / inv_cell_ + halo_;
  }
  const double ex = std::max(std::max(-fx, fx - nx_), 0.0), ey = std::max(std::max(-fy, fy - ny_), 0.0);
  return std::sqrt(ex * ex + ey * ey) / inv_cell_;
}

}  // namespace softdrop
