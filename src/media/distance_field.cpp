// The signed distance field of an image medium (distance_field.hpp): exact Euclidean distance
// transforms of the pixel centres (Felzenszwalb and Huttenlocher, "Distance transforms of sampled
// functions", 2012), one for the solid and one for the pore.
#include "media/distance_field.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

namespace softdrop {
namespace {

// "No feature" in a squared distance: larger than any squared distance in an image, small enough
// that sums of it stay finite.
constexpr double kFar = 1e20;

// The 1D squared distance transform of f (n samples) into d: d[q] = min_p (q - p)^2 + f[p].
void transform_1d(const double* f, int n, double* d, std::vector<int>& v, std::vector<double>& z) {
  v.assign(static_cast<std::size_t>(n), 0);
  z.assign(static_cast<std::size_t>(n) + 1, 0);
  const auto parabola = [&](int q, int p) {  // where the parabolas from q and p cross
    return ((f[q] + static_cast<double>(q) * q) - (f[p] + static_cast<double>(p) * p)) / (2.0 * (q - p));
  };
  int k = 0;
  z[0] = -HUGE_VAL;
  z[1] = HUGE_VAL;
  for (int q = 1; q < n; ++q) {
    double s = parabola(q, v[static_cast<std::size_t>(k)]);
    while (s <= z[static_cast<std::size_t>(k)]) s = parabola(q, v[static_cast<std::size_t>(--k)]);
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = s;
    z[static_cast<std::size_t>(k) + 1] = HUGE_VAL;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(k) + 1] < q) ++k;
    const int p = v[static_cast<std::size_t>(k)];
    d[q] = static_cast<double>(q - p) * (q - p) + f[p];
  }
}

// Squared distance (in pixels) from each pixel centre to the nearest centre where `feature`
// holds, over an nx x rows grid, periodic in x or not.
std::vector<double> squared_distance(const std::vector<std::uint8_t>& feature, int nx, int rows, bool periodic) {
  std::vector<double> g(feature.size());
  std::vector<int> v;
  std::vector<double> z;
  std::vector<double> f(static_cast<std::size_t>(std::max(rows, 3 * nx))), d(f.size());
  for (int i = 0; i < nx; ++i) {  // along each column
    for (int j = 0; j < rows; ++j)
      f[static_cast<std::size_t>(j)] = feature[i + static_cast<std::size_t>(nx) * j] ? 0 : kFar;
    transform_1d(f.data(), rows, d.data(), v, z);
    for (int j = 0; j < rows; ++j) g[i + static_cast<std::size_t>(nx) * j] = d[static_cast<std::size_t>(j)];
  }
  // Along each row; a periodic row is laid out three times, and its middle copy read.
  const int copies = periodic ? 3 : 1, n = copies * nx, offset = periodic ? nx : 0;
  for (int j = 0; j < rows; ++j) {
    const double* row = g.data() + static_cast<std::size_t>(nx) * j;
    for (int c = 0; c < copies; ++c) std::copy(row, row + nx, f.begin() + static_cast<std::ptrdiff_t>(c) * nx);
    transform_1d(f.data(), n, d.data(), v, z);
    std::copy(d.begin() + offset, d.begin() + offset + nx, g.begin() + static_cast<std::ptrdiff_t>(nx) * j);
  }
  return g;
}

}  // namespace

// kPadding, the rows of pore added above and below the image: a mass above or below it by a
// pixel or more touches nothing, and the field is whole where it can be.
DistanceField::DistanceField(const PoreImage& im)
    : nx_(im.nx), rows_(im.ny + 2 * kPadding), h_(im.pixel), periodic_(im.periodic) {
  const std::size_t size = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(rows_);
  std::vector<std::uint8_t> pore(size, 1);
  std::copy(im.pore.begin(), im.pore.end(), pore.begin() + static_cast<std::ptrdiff_t>(nx_) * kPadding);
  std::vector<std::uint8_t> solid(size);
  for (std::size_t k = 0; k < size; ++k) solid[k] = pore[k] ? 0 : 1;
  const std::vector<double> to_solid = squared_distance(solid, nx_, rows_, periodic_);
  const std::vector<double> to_pore = squared_distance(pore, nx_, rows_, periodic_);
  // The surface lies half a pixel from the centres on either side of it.
  const double far = 4.0 * (nx_ + rows_) * h_;
  d_.resize(size);
  for (std::size_t k = 0; k < size; ++k) {
    if (pore[k])
      d_[k] = static_cast<float>(to_solid[k] >= 0.5 * kFar ? far : (std::sqrt(to_solid[k]) - 0.5) * h_);
    else
      d_[k] = static_cast<float>(-(std::sqrt(to_pore[k]) - 0.5) * h_);
  }
  normals();
  // The solid's connected parts, 8-neighbour, in the order of their first pixel, with their
  // extents: the fill follows a part across the seam in unwrapped columns.
  part_.assign(size, -1);
  std::vector<std::pair<std::size_t, int>> stack;  // a pixel and its unwrapped column
  for (std::size_t start = 0; start < size; ++start) {
    if (!solid[start] || part_[start] >= 0) continue;
    part_[start] = parts_;
    const int i0 = static_cast<int>(start % static_cast<std::size_t>(nx_)),
              j0 = static_cast<int>(start / static_cast<std::size_t>(nx_));
    int lo_i = i0, hi_i = i0, lo_j = j0, hi_j = j0;
    stack.emplace_back(start, i0);
    while (!stack.empty()) {
      const auto [k, ui] = stack.back();
      stack.pop_back();
      const int j = static_cast<int>(k / static_cast<std::size_t>(nx_));
      lo_i = std::min(lo_i, ui), hi_i = std::max(hi_i, ui), lo_j = std::min(lo_j, j), hi_j = std::max(hi_j, j);
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          int ii = (ui + di) % nx_;
          if (ii < 0) ii += nx_;
          const int jj = j + dj;
          if (jj < 0 || jj >= rows_) continue;
          if (!periodic_ && (ui + di < 0 || ui + di >= nx_)) continue;
          const std::size_t n = static_cast<std::size_t>(ii) + static_cast<std::size_t>(nx_) * jj;
          if (solid[n] && part_[n] < 0) {
            part_[n] = parts_;
            stack.emplace_back(n, ui + di);
          }
        }
    }
    extents_.push_back({(hi_i - lo_i + 1) * h_, (hi_j - lo_j + 1) * h_, i0, j0 - kPadding});
    ++parts_;
  }
}

void DistanceField::normals() {
  // The field smoothed by the binomial filter (1 4 6 4 1) / 16 along x and y, twice (a Gaussian
  // of about 1.4 pixels): a linear field (a flat surface) is left as it is, and the staircase's
  // ripples are damped, which would otherwise tilt the normal by up to 15 degrees at any
  // resolution (bench/README.md, "Image media").
  constexpr int passes = 2;
  std::vector<double> smooth(d_.begin(), d_.end()), t(d_.size());
  const double w[5] = {1 / 16.0, 4 / 16.0, 6 / 16.0, 4 / 16.0, 1 / 16.0};
  const auto column = [&](int i) { return periodic_ ? (i + nx_) % nx_ : std::clamp(i, 0, nx_ - 1); };
  const auto at = [&](int i, int j) { return static_cast<std::size_t>(i) + static_cast<std::size_t>(nx_) * j; };
  for (int pass = 0; pass < passes; ++pass) {
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < nx_; ++i) {
        double sum = 0;
        for (int k = -2; k <= 2; ++k) sum += w[k + 2] * smooth[at(column(i + k), j)];
        t[at(i, j)] = sum;
      }
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < nx_; ++i) {
        double sum = 0;
        for (int k = -2; k <= 2; ++k) sum += w[k + 2] * t[at(i, std::clamp(j + k, 0, rows_ - 1))];
        smooth[at(i, j)] = sum;
      }
  }
  // Its gradient by central differences (one-sided at the padding's edges and at walls).
  gx_.resize(d_.size());
  gy_.resize(d_.size());
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const int l = periodic_ ? column(i - 1) : std::max(i - 1, 0),
                r = periodic_ ? column(i + 1) : std::min(i + 1, nx_ - 1);
      const int b = std::max(j - 1, 0), u = std::min(j + 1, rows_ - 1);
      gx_[at(i, j)] = static_cast<float>((smooth[at(r, j)] - smooth[at(l, j)]) / (periodic_ ? 2 : std::max(1, r - l)));
      gy_[at(i, j)] = static_cast<float>((smooth[at(i, u)] - smooth[at(i, b)]) / std::max(1, u - b));
    }
}

bool DistanceField::sample(double x, double y, Sample* s) const {
  const double v = y / h_ - 0.5 + kPadding;
  if (!(v >= 0 && v < rows_ - 1)) return false;  // also NaN
  const double u = std::clamp(x / h_ - 0.5, -1.0, static_cast<double>(nx_));
  if (std::isnan(u)) return false;
  const int j0 = static_cast<int>(v);
  int i0 = static_cast<int>(std::floor(u));
  const double fx = u - i0, fy = v - j0;
  int i1 = i0 + 1;
  if (periodic_) {
    i0 = (i0 + nx_) % nx_;
    i1 = i1 % nx_;
  } else {
    i0 = std::clamp(i0, 0, nx_ - 1);
    i1 = std::clamp(i1, 0, nx_ - 1);
  }
  const std::size_t r0 = static_cast<std::size_t>(nx_) * j0, r1 = r0 + static_cast<std::size_t>(nx_);
  const double d00 = d_[r0 + i0], d10 = d_[r0 + i1], d01 = d_[r1 + i0], d11 = d_[r1 + i1];  // floats, exactly
  if (d00 >= 0 && d10 >= 0 && d01 >= 0 && d11 >= 0) return false;
  const double d = (1 - fy) * ((1 - fx) * d00 + fx * d10) + fy * ((1 - fx) * d01 + fx * d11);
  if (!(d < 0)) return false;
  const auto blend = [&](const std::vector<float>& g) {
    return (1 - fy) * ((1 - fx) * g[r0 + i0] + fx * g[r0 + i1]) + fy * ((1 - fx) * g[r1 + i0] + fx * g[r1 + i1]);
  };
  const double gx = blend(gx_), gy = blend(gy_);
  const double g = std::hypot(gx, gy);
  s->d = d;
  s->nx = g > 0 ? gx / g : 0.0;
  s->ny = g > 0 ? gy / g : 1.0;
  // The part of the deepest corner, which is solid since d < 0.
  std::size_t deepest = r0 + i0;
  float least = d_[deepest];
  for (const std::size_t k : {r0 + i1, r1 + i0, r1 + i1})
    if (d_[k] < least) least = d_[k], deepest = k;
  s->part = part_[deepest];  // solid: its d is at most -h/2
  return true;
}

std::shared_ptr<const DistanceField> DistanceField::of(const std::shared_ptr<const PoreImage>& image) {
  static std::mutex mutex;
  static std::vector<std::pair<std::weak_ptr<const PoreImage>, std::shared_ptr<const DistanceField>>> built;
  std::lock_guard lock(mutex);
  std::erase_if(built, [](const auto& e) { return e.first.expired(); });
  for (const auto& [owner, field] : built)
    if (!owner.owner_before(image) && !image.owner_before(owner)) return field;
  auto field = std::make_shared<const DistanceField>(*image);
  built.emplace_back(image, field);
  return field;
}

}  // namespace softdrop
