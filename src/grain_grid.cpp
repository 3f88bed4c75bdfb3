#include "softdrop/grain_grid.hpp"

#include <algorithm>
#include <cmath>

namespace softdrop {

GrainGrid::GrainGrid(const Medium& medium, double cell_size) {
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
  inv_cell_ = 1.0 / cell_size;
  nx_ = std::max(1, static_cast<int>(std::ceil((xmax - xmin) * inv_cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((ymax - ymin) * inv_cell_)));
  const std::int64_t cells = static_cast<std::int64_t>(nx_) * ny_;

  auto cell_span = [&](std::size_t k, int* ix0, int* ix1, int* iy0, int* iy1) {
    *ix0 = std::clamp(static_cast<int>((gx_[k] - gr_[k] - x0_) * inv_cell_), 0, nx_ - 1);
    *ix1 = std::clamp(static_cast<int>((gx_[k] + gr_[k] - x0_) * inv_cell_), 0, nx_ - 1);
    *iy0 = std::clamp(static_cast<int>((gy_[k] - gr_[k] - y0_) * inv_cell_), 0, ny_ - 1);
    *iy1 = std::clamp(static_cast<int>((gy_[k] + gr_[k] - y0_) * inv_cell_), 0, ny_ - 1);
  };
  start_.assign(static_cast<std::size_t>(cells + 1), 0);
  for (std::size_t k = 0; k < gx_.size(); ++k) {
    int ix0, ix1, iy0, iy1;
    cell_span(k, &ix0, &ix1, &iy0, &iy1);
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix) ++start_[static_cast<std::size_t>(iy) * nx_ + ix + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
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
}

}  // namespace softdrop
