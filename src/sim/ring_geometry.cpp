// Geometry of a ring: its area, whether it crosses itself, whether it holds a point.
#include "lane_policy.hpp"
#include "lane_scalar.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/droplet.hpp"

namespace softdrop {
namespace {
// Orientation sign of (a, b, c).
double cross(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}
}  // namespace

double ring_area(const DropletState& s) {
  const int n = s.size();
  double twice = 0;
  for (int i = 0, j = n - 1; i < n; j = i++) twice += lanes::scalar::shoelace_term(s.x[i], s.y[i], s.x[j], s.y[j]);
  return 0.5 * twice;
}

namespace {
// Whether segment (a, b) properly crosses segment (c, d), as signs of cross products; (c, d) is
// tested against the line of (a, b) first, which rules out most pairs.
inline bool crosses(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
  const double d1 = cross(ax, ay, bx, by, cx, cy);
  const double d2 = cross(ax, ay, bx, by, dx, dy);
  if ((d1 > 0) == (d2 > 0) || d1 == 0 || d2 == 0) return false;
  const double d3 = cross(cx, cy, dx, dy, ax, ay);
  const double d4 = cross(cx, cy, dx, dy, bx, by);
  return (d3 > 0) != (d4 > 0) && d3 != 0 && d4 != 0;
}
}  // namespace

#if defined(SOFTDROP_AVX_DISPATCH)
namespace {
// Whether segment (a, b) properly crosses one of the edges (x[j], y[j])-(x[j + 1], y[j + 1]) for j
// from `first`, four at a time while four remain before `last`: crosses() on each lane, the same
// operations, so the same answer. Sets *done to the first j it did not look at.
SOFTDROP_AVX bool crosses_any_of_four(double ax, double ay, double bx, double by, const double* x, const double* y,
                                      int first, int last, int* done) {
  const __m256d zero = _mm256_setzero_pd(), Ax = _mm256_set1_pd(ax), Ay = _mm256_set1_pd(ay);
  const __m256d Bx = _mm256_set1_pd(bx), By = _mm256_set1_pd(by);
  const __m256d ux = _mm256_set1_pd(bx - ax), uy = _mm256_set1_pd(by - ay);
  // Lanes where (d > 0) != (e > 0), d != 0 and e != 0 (NaN: not > 0, and not == 0).
  const auto opposite = [&](__m256d d, __m256d e) SOFTDROP_AVX {
    const __m256d sides = _mm256_xor_pd(_mm256_cmp_pd(d, zero, _CMP_GT_OQ), _mm256_cmp_pd(e, zero, _CMP_GT_OQ));
    return _mm256_and_pd(sides,
                         _mm256_and_pd(_mm256_cmp_pd(d, zero, _CMP_NEQ_UQ), _mm256_cmp_pd(e, zero, _CMP_NEQ_UQ)));
  };
  int j = first;
  for (; j + 4 <= last; j += 4) {
    const __m256d cx = _mm256_loadu_pd(x + j), cy = _mm256_loadu_pd(y + j);
    const __m256d dx = _mm256_loadu_pd(x + j + 1), dy = _mm256_loadu_pd(y + j + 1);
    // cross(a, b, c) and cross(a, b, d)
    const __m256d d1 =
        _mm256_sub_pd(_mm256_mul_pd(ux, _mm256_sub_pd(cy, Ay)), _mm256_mul_pd(uy, _mm256_sub_pd(cx, Ax)));
    const __m256d d2 =
        _mm256_sub_pd(_mm256_mul_pd(ux, _mm256_sub_pd(dy, Ay)), _mm256_mul_pd(uy, _mm256_sub_pd(dx, Ax)));
    const __m256d across = opposite(d1, d2);
    if (_mm256_movemask_pd(across) == 0) continue;
    // cross(c, d, a) and cross(c, d, b)
    const __m256d vx = _mm256_sub_pd(dx, cx), vy = _mm256_sub_pd(dy, cy);
    const __m256d d3 =
        _mm256_sub_pd(_mm256_mul_pd(vx, _mm256_sub_pd(Ay, cy)), _mm256_mul_pd(vy, _mm256_sub_pd(Ax, cx)));
    const __m256d d4 =
        _mm256_sub_pd(_mm256_mul_pd(vx, _mm256_sub_pd(By, cy)), _mm256_mul_pd(vy, _mm256_sub_pd(Bx, cx)));
    if (_mm256_movemask_pd(_mm256_and_pd(across, opposite(d3, d4))) != 0) return true;
  }
  *done = j;
  return false;
}
}  // namespace
#endif

bool ring_self_intersects(const DropletState& s) {
  // Every pair of edges that share no mass: edge i runs from mass i to i + 1 (the last to mass 0).
  const int n = s.size();
  const double *x = s.x.data(), *y = s.y.data();
#if defined(SOFTDROP_AVX_DISPATCH)
  const bool four = static_cast<int>(constraint_vector_width()) >= 4;
#endif
  for (int i = 0; i + 2 < n; ++i) {
    const double ax = x[i], ay = y[i], bx = x[i + 1], by = y[i + 1];
    int j = i + 2;
#if defined(SOFTDROP_AVX_DISPATCH)
    if (four && crosses_any_of_four(ax, ay, bx, by, x, y, j, n - 1, &j)) return true;
#endif
    for (; j + 1 < n; ++j)
      if (crosses(ax, ay, bx, by, x[j], y[j], x[j + 1], y[j + 1])) return true;
    // The closing edge (n - 1, 0) shares mass 0 with edge 0.
    if (i > 0 && crosses(ax, ay, bx, by, x[n - 1], y[n - 1], x[0], y[0])) return true;
  }
  return false;
}

bool ring_contains(const DropletState& s, double px, double py) {
  const int n = s.size();
  bool inside = false;
  for (int i = 0, j = n - 1; i < n; j = i++) {
    if ((s.y[i] > py) != (s.y[j] > py) && px < (s.x[j] - s.x[i]) * (py - s.y[i]) / (s.y[j] - s.y[i]) + s.x[i])
      inside = !inside;
  }
  return inside;
}

}  // namespace softdrop
