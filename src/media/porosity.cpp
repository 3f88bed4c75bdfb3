#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "grain_grid.hpp"
#include "softdrop/medium.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {

constexpr double kTwoPi = 2 * M_PI;

// Angular intervals on a circle; `full` once the whole circle is covered.
struct ArcCover {
  std::vector<std::pair<double, double>> spans;
  bool full = false;
  void clear() {
    spans.clear();
    full = false;
  }
  // Covers [centre - half, centre + half].
  void add(double centre, double half) {
    if (half <= 0) return;
    if (half >= M_PI) {
      full = true;
      return;
    }
    double a = std::fmod(centre - half, kTwoPi);
    if (a < 0) a += kTwoPi;
    const double b = a + 2 * half;
    if (b <= kTwoPi) {
      spans.emplace_back(a, b);
    } else {
      spans.emplace_back(a, kTwoPi);
      spans.emplace_back(0, b - kTwoPi);
    }
  }
};

// Integral of (x dy - y dx) / 2 along the circle (cx, cy, r) from angle a to b, counter-clockwise.
double arc_term(double cx, double cy, double r, double a, double b) {
  return 0.5 * (r * r * (b - a) + r * cx * (std::sin(b) - std::sin(a)) - r * cy * (std::cos(b) - std::cos(a)));
}

// Length of the union of intervals clipped to [lo, hi].
double covered_length(std::vector<std::pair<double, double>>& iv, double lo, double hi) {
  std::sort(iv.begin(), iv.end());
  double total = 0, cur_a = 0, cur_b = 0;
  bool open = false;
  for (auto [a, b] : iv) {
    a = std::max(a, lo);
    b = std::min(b, hi);
    if (b <= a) continue;
    if (open && a <= cur_b) {
      cur_b = std::max(cur_b, b);
    } else {
      if (open) total += cur_b - cur_a;
      cur_a = a;
      cur_b = b;
      open = true;
    }
  }
  if (open) total += cur_b - cur_a;
  return total;
}

}  // namespace

double solid_area(const Medium& medium) {
  if (medium.image) return (1.0 - medium.image->porosity()) * medium.width * medium.height;  // pixel by pixel
  const GrainGrid grid(medium);
  const auto &gx = grid.gx(), &gy = grid.gy(), &gr = grid.gr();
  const std::size_t n = gx.size();
  const double W = medium.width, H = medium.height;
  double area = 0;
  ArcCover cover;
  std::vector<std::int64_t> seen(n, -1);
  std::vector<std::pair<double, double>> right_edge, top_edge;
  for (std::size_t i = 0; i < n; ++i) {
    const double cx = gx[i], cy = gy[i], r = gr[i];
    // Box edges x = W and y = H: covered lengths enter Green's theorem (the edges x = 0 and y = 0
    // contribute nothing).
    if (std::abs(W - cx) < r) {
      const double h = std::sqrt(r * r - (W - cx) * (W - cx));
      right_edge.emplace_back(cy - h, cy + h);
    }
    if (std::abs(H - cy) < r) {
      const double h = std::sqrt(r * r - (H - cy) * (H - cy));
      top_edge.emplace_back(cx - h, cx + h);
    }
    cover.clear();
    // Parts of the circle outside the box.
    auto clip = [&](double c, double centre_angle, bool cosine) {
      // Covers angles where (cos or sin)(theta) lies beyond c, i.e. outside the box edge.
      if (c >= 1) return;
      if (c <= -1) {
        cover.full = true;
        return;
      }
      const double half = cosine ? std::acos(c) : M_PI / 2 - std::asin(c);
      cover.add(centre_angle, half);
    };
    clip((W - cx) / r, 0, true);          // x > W: cos > (W - cx) / r
    clip(cx / r, M_PI, true);             // x < 0: cos < -cx / r, i.e. cos(theta - pi) > cx / r
    clip((H - cy) / r, M_PI / 2, false);  // y > H
    clip(cy / r, 3 * M_PI / 2, false);    // y < 0
    if (cover.full) continue;
    // Parts covered by other discs, found through the grid cells this disc overlaps.
    const double cell = grid.cell_size();
    for (double qy = cy - r; qy < cy + r + cell && !cover.full; qy += cell) {
      for (double qx = cx - r; qx < cx + r + cell && !cover.full; qx += cell) {
        const auto range = grid.query(std::min(qx, cx + r), std::min(qy, cy + r));
        for (const std::int32_t* it = range.begin; it != range.end; ++it) {
          const std::size_t j = static_cast<std::size_t>(*it);
          if (j == i || seen[j] == static_cast<std::int64_t>(i)) continue;
          seen[j] = static_cast<std::int64_t>(i);
          const double dx = gx[j] - cx, dy = gy[j] - cy, rj = gr[j];
          const double d2 = dx * dx + dy * dy;
          if (d2 >= (r + rj) * (r + rj)) continue;
          const double d = std::sqrt(d2);
          if (d == 0 && rj == r) {
            if (j < i) cover.full = true;  // an identical disc: the first copy keeps the arc
            continue;
          }
          if (d + r <= rj) {
            cover.full = true;
            break;
          }
          if (d + rj <= r) continue;
          const double c = std::clamp((d2 + r * r - rj * rj) / (2 * d * r), -1.0, 1.0);
          cover.add(std::atan2(dy, dx), std::acos(c));
        }
      }
    }
    if (cover.full) continue;
    // Integrate over the uncovered arcs.
    std::sort(cover.spans.begin(), cover.spans.end());
    double pos = 0;
    for (const auto& [a, b] : cover.spans) {
      if (a > pos) area += arc_term(cx, cy, r, pos, a);
      pos = std::max(pos, b);
    }
    if (pos < kTwoPi) area += arc_term(cx, cy, r, pos, kTwoPi);
  }
  area += 0.5 * W * covered_length(right_edge, 0, H) + 0.5 * H * covered_length(top_edge, 0, W);
  return area;
}

double exact_porosity(const Medium& medium) {
  if (medium.image) return medium.image->porosity();
  return 1.0 - solid_area(medium) / (medium.width * medium.height);
}

PorosityEstimate monte_carlo_porosity(const Medium& medium, std::int64_t samples, std::uint64_t seed) {
  const GrainGrid grid(medium);
  Rng rng(seed);
  std::int64_t voids = 0;
  for (std::int64_t s = 0; s < samples; ++s) {
    const double x = rng.uniform(0, medium.width), y = rng.uniform(0, medium.height);
    bool solid = false;
    if (const PoreImage* im = medium.image.get()) {  // the pixel the point falls in
      const int i = std::min(im->nx - 1, static_cast<int>(x / im->pixel));
      const int j = std::min(im->ny - 1, static_cast<int>(y / im->pixel));
      solid =
          im->pore[static_cast<std::size_t>(i) + static_cast<std::size_t>(im->nx) * static_cast<std::size_t>(j)] == 0;
    }
    const auto range = grid.query(x, y);
    for (const std::int32_t* it = range.begin; it != range.end && !solid; ++it) {
      const double dx = x - grid.gx()[*it], dy = y - grid.gy()[*it], r = grid.gr()[*it];
      solid = dx * dx + dy * dy < r * r;
    }
    voids += solid ? 0 : 1;
  }
  const double p = static_cast<double>(voids) / static_cast<double>(samples);
  return {p, std::sqrt(p * (1 - p) / static_cast<double>(samples))};
}

}  // namespace softdrop
