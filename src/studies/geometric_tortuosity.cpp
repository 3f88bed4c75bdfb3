// The geometric tortuosity of a pore image (pore_tortuosity.hpp): the distance through the pore
// space from every pixel centre to the bottom edge by fast marching, read at the top row.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pore_grid.hpp"
#include "softdrop/pore_tortuosity.hpp"

namespace softdrop {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// The distance field: first-order upwind solution of |grad d| = 1 on the pore pixels, d = h / 2
// at the bottom row's centres (half a pixel above the edge). Pixels are taken in increasing d, ties
// by index, so the field is the same on every run.
std::vector<double> distance_to_bottom(const PoreImage& im) {
  const int nx = im.nx, ny = im.ny;
  const double h = im.pixel;
  std::vector<double> d(im.pore.size(), kFar);
  std::vector<std::uint8_t> done(im.pore.size(), 0);
  using Entry = std::pair<double, std::int64_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> trial;
  for (int i = 0; i < nx; ++i)
    if (im.pore[static_cast<std::size_t>(i)]) {
      d[static_cast<std::size_t>(i)] = 0.5 * h;
      trial.push({0.5 * h, i});
    }
  auto at = [&](int i, int j) -> double {  // a neighbour's accepted distance (kFar: none, solid or outside)
    if (j < 0 || j >= ny) return kFar;
    if (i < 0 || i >= nx) {
      if (!im.periodic) return kFar;
      i = (i + nx) % nx;
    }
    const auto k = static_cast<std::size_t>(i + nx * j);
    return done[k] ? d[k] : kFar;
  };
  while (!trial.empty()) {
    const auto [dk, k] = trial.top();
    trial.pop();
    const auto uk = static_cast<std::size_t>(k);
    if (done[uk] || dk > d[uk]) continue;
    done[uk] = 1;
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    for (int n = 0; n < 4; ++n) {
      const std::int64_t neighbour = detail::face_neighbour(im, i, j, n);
      if (neighbour < 0) continue;
      const auto un = static_cast<std::size_t>(neighbour);
      const int ii = static_cast<int>(neighbour % nx), jj = static_cast<int>(neighbour / nx);
      if (!im.pore[un] || done[un]) continue;
      const double a = std::min(at(ii - 1, jj), at(ii + 1, jj)), b = std::min(at(ii, jj - 1), at(ii, jj + 1));
      double v;
      if (std::abs(a - b) >= h || !std::isfinite(a) || !std::isfinite(b)) {
        v = std::min(a, b) + h;
      } else {
        v = 0.5 * (a + b + std::sqrt(2 * h * h - (a - b) * (a - b)));
      }
      if (v < d[un]) {
        d[un] = v;
        trial.push({v, static_cast<std::int64_t>(un)});
      }
    }
  }
  return d;
}

}  // namespace

GeometricTortuosity geometric_tortuosity(const PoreImage& image) {
  std::string why;
  if (!image.IsValid(&why)) throw std::invalid_argument(why);
  std::vector<double> d = distance_to_bottom(image);
  const double height = image.ny * image.pixel;
  GeometricTortuosity g;
  double sum = 0, sum2 = 0;
  g.shortest = kFar;
  for (int i = 0; i < image.nx; ++i) {
    const auto k = static_cast<std::size_t>(i + image.nx * (image.ny - 1));
    if (!image.pore[k]) continue;
    ++g.starts;
    if (!std::isfinite(d[k])) continue;
    ++g.connected;
    const double t = (d[k] + 0.5 * image.pixel) / height;  // from the top edge, half a pixel above the centre
    sum += t, sum2 += t * t;
    g.shortest = std::min(g.shortest, t);
    g.longest = std::max(g.longest, t);
  }
  if (g.connected == 0)
    throw std::invalid_argument(g.starts == 0 ? "image: no pore pixel in the top row"
                                              : "image: no pore path from the top to the bottom");
  const double n = g.connected;
  g.tortuosity = sum / n;
  g.standard_error = n > 1 ? std::sqrt(std::max(0.0, (sum2 - sum * sum / n) / (n - 1)) / n) : 0.0;
  g.distance = std::move(d);
  return g;
}

}  // namespace softdrop
