#include "media/relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "spacing.hpp"

namespace softdrop::detail {
namespace {

// The box's hold on a grain: inside in y, and inside in x too unless the box is periodic in x,
// where the centre wraps into [0, width).
void confine(Grain& g, double width, double height, bool periodic) {
  g.y = std::clamp(g.y, g.r, height - g.r);
  if (!periodic) {
    g.x = std::clamp(g.x, g.r, width - g.r);
    return;
  }
  g.x -= width * std::floor(g.x / width);
  if (g.x >= width) g.x -= width;  // a tiny negative x rounds up to width itself
}

// The pairs of grains near enough to break the rule: those in the same or neighbouring cells of
// a grid whose cells are at least the largest required distance wide. Sorted, each pair once.
class PairGrid {
 public:
  PairGrid(double width, double height, bool periodic, double reach)
      : width_(width),
        height_(height),
        periodic_(periodic),
        nx_(std::max(1, static_cast<int>(width / reach))),
        ny_(std::max(1, static_cast<int>(height / reach))),
        cells_(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_)) {}

  const std::vector<std::pair<int, int>>& pairs(const std::vector<Grain>& grains) {
    for (auto& cell : cells_) cell.clear();
    for (int i = 0; i < static_cast<int>(grains.size()); ++i)
      cells_[cell_of(grains[static_cast<std::size_t>(i)])].push_back(i);
    pairs_.clear();
    for (int cy = 0; cy < ny_; ++cy)
      for (int cx = 0; cx < nx_; ++cx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            int ox = cx + dx;
            const int oy = cy + dy;
            if (oy < 0 || oy >= ny_) continue;
            if (ox < 0 || ox >= nx_) {
              if (!periodic_) continue;
              ox = (ox + nx_) % nx_;
            }
            for (int i : cells_[index(cx, cy)])
              for (int j : cells_[index(ox, oy)])
                if (i < j) pairs_.emplace_back(i, j);
          }
    std::sort(pairs_.begin(), pairs_.end());  // a narrow periodic grid meets a pair twice
    pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
    return pairs_;
  }

 private:
  std::size_t index(int cx, int cy) const {
    return static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx);
  }
  std::size_t cell_of(const Grain& g) const {
    const int cx = std::clamp(static_cast<int>(g.x / width_ * nx_), 0, nx_ - 1);
    const int cy = std::clamp(static_cast<int>(g.y / height_ * ny_), 0, ny_ - 1);
    return index(cx, cy);
  }

  double width_, height_;
  bool periodic_;
  int nx_, ny_;
  std::vector<std::vector<int>> cells_;
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace

bool relax_spacing(std::vector<Grain>& grains, double width, double height, bool periodic, double gap, int max_sweeps) {
  double r_max = 0;
  for (Grain& g : grains) {
    r_max = std::max(r_max, g.r);
    confine(g, width, height, periodic);
  }
  PairGrid grid(width, height, periodic, required_distance(r_max, r_max, gap));
  // Each pair found too close is pushed apart along its centre line, half the shortfall each, to
  // a hair past the required distance, so that rounding leaves it clear of the rule. A sweep that
  // moves nothing used pairs found at the positions it ends with, so the rule then holds for all.
  constexpr double kClear = 1 + 1e-9;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool moved = false;
    for (const auto& [i, j] : grid.pairs(grains)) {
      Grain& a = grains[static_cast<std::size_t>(i)];
      Grain& b = grains[static_cast<std::size_t>(j)];
      double dx = b.x - a.x;
      if (periodic) dx -= width * std::round(dx / width);
      const double dy = b.y - a.y;
      const double need = required_distance(a.r, b.r, gap);
      const double d2 = dx * dx + dy * dy;
      if (d2 >= need * need) continue;
      moved = true;
      const double d = std::sqrt(d2);
      const double ux = d > 0 ? dx / d : 1.0, uy = d > 0 ? dy / d : 0.0;  // coincident: apart in x
      const double push = 0.5 * (need * kClear - d);
      a.x -= push * ux, a.y -= push * uy;
      b.x += push * ux, b.y += push * uy;
      confine(a, width, height, periodic);
      confine(b, width, height, periodic);
    }
    if (!moved) return true;
  }
  return false;
}

}  // namespace softdrop::detail
