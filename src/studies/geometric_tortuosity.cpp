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
#include "pore_tortuosity.hpp"

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

std::vector<PorePath> shortest_paths(const PoreImage& image, const GeometricTortuosity& g, int count) {
  if (g.distance.size() != image.pore.size())
    throw std::invalid_argument("shortest paths: a distance field of another image");
  const int nx = image.nx, ny = image.ny;
  const double h = image.pixel;
  std::vector<int> starts;
  for (int i = 0; i < nx; ++i)
    if (std::isfinite(g.distance[static_cast<std::size_t>(i + nx * (ny - 1))])) starts.push_back(i);
  std::vector<PorePath> paths;
  const int n = std::min<int>(count, static_cast<int>(starts.size()));
  for (int p = 0; p < n; ++p) {
    int i = starts[static_cast<std::size_t>((2 * p + 1) * static_cast<std::int64_t>(starts.size()) / (2 * n))];
    int j = ny - 1, laps = 0;  // laps: times the path crossed a periodic side (x unwrapped)
    PorePath path;
    auto add = [&](double y) {
      path.x.push_back((i + 0.5 + static_cast<double>(laps) * nx) * h);
      path.y.push_back(y);
    };
    add(ny * h);
    for (std::int64_t steps = 0; steps <= static_cast<std::int64_t>(nx) * ny; ++steps) {
      add((j + 0.5) * h);
      if (j == 0) break;
      // The steepest way down: the largest fall of the distance per length of the step, so that
      // straight steps win over diagonal ones of the same fall.
      const double here = g.distance[static_cast<std::size_t>(i + nx * j)];
      double best = 0;
      int bi = -1, bj = -1, bl = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          int ii = i + di, lap = 0;
          const int jj = j + dj;
          if ((di == 0 && dj == 0) || jj < 0 || jj >= ny) continue;
          if (ii < 0 || ii >= nx) {
            if (!image.periodic) continue;
            lap = ii < 0 ? -1 : 1;
            ii -= lap * nx;
          }
          const double fall = (here - g.distance[static_cast<std::size_t>(ii + nx * jj)]) / std::hypot(di, dj);
          if (fall > best) best = fall, bi = ii, bj = jj, bl = lap;
        }
      if (bi < 0) break;  // no neighbour nearer the bottom: cannot happen off the bottom row
      i = bi, j = bj, laps += bl;
    }
    add(0);
    paths.push_back(std::move(path));
  }
  return paths;
}

}  // namespace softdrop
