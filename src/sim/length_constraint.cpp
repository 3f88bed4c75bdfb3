// The length constraint on one ring: passes of single-spring corrections (spring_correction.hpp)
// in the sequential or the red-black order, and the choice of vector width for every constraint.
#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

#include "lane_simd.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/droplet.hpp"
#include "spring_correction.hpp"

namespace softdrop {
using constraint_detail::constrain;
using constraint_detail::constrain_ends;
namespace {

// The vector width in use: the processor's widest, unless narrowed by
// limit_constraint_vector_width.
int machine_width() {
#if defined(SOFTDROP_AVX_DISPATCH)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return 8;
  if (__builtin_cpu_supports("avx")) return 4;
  return 2;
#else
  return 1;
#endif
}
std::atomic<int> width_limit{8};
int vector_width() {
  static const int machine = machine_width();
  return std::min(machine, width_limit.load(std::memory_order_relaxed));
}

#if defined(SOFTDROP_AVX_DISPATCH)
// Two, four and eight springs at once: the kernel of lane_simd.hpp (spring_kernel.inc), shared
// with the lane-by-lane step.

// The red-black half-pass four springs at a time, from spring 0 while four remain; returns the
// corrections and sets *done to the springs it did. The correction is the one kernel of every
// width; this driver and the eight- and two-spring ones below differ only in how each width splits
// interleaved pairs of ends into lanes (unpacks within 128-bit halves, two-source permutes), which
// no common vector operation expresses.
SOFTDROP_AVX int constrain_disjoint_quads(double* x, double* y, int count, double dmin, double dmax, int* done) {
  lanes::avx4::Limits l;
  lanes::avx4::set_limits(&l, dmin, dmax);
  int changed = 0, k = 0;
  for (; k + 4 <= count; k += 4) {
    double* px = x + 2 * k;
    double* py = y + 2 * k;
    // (x_i0 x_j0 | x_i1 x_j1), (x_i2 x_j2 | x_i3 x_j3): unpacking works within 128-bit halves, so
    // the lanes hold springs (0, 2 | 1, 3), and unpacking back restores the layout.
    const __m256d xa = _mm256_loadu_pd(px), xb = _mm256_loadu_pd(px + 4);
    const __m256d ya = _mm256_loadu_pd(py), yb = _mm256_loadu_pd(py + 4);
    __m256d xi = _mm256_unpacklo_pd(xa, xb), xj = _mm256_unpackhi_pd(xa, xb);
    __m256d yi = _mm256_unpacklo_pd(ya, yb), yj = _mm256_unpackhi_pd(ya, yb);
    const unsigned moved = lanes::avx4::bits(lanes::avx4::constrain_springs(l, &xi, &yi, &xj, &yj));
    if (moved == 0) continue;
    changed += __builtin_popcount(moved);
    _mm256_storeu_pd(px, _mm256_unpacklo_pd(xi, xj));
    _mm256_storeu_pd(px + 4, _mm256_unpackhi_pd(xi, xj));
    _mm256_storeu_pd(py, _mm256_unpacklo_pd(yi, yj));
    _mm256_storeu_pd(py + 4, _mm256_unpackhi_pd(yi, yj));
  }
  *done = k;
  return changed;
}
#endif

#if defined(SOFTDROP_AVX_DISPATCH)

// constrain_disjoint_quads() eight springs at a time.
SOFTDROP_AVX512 int constrain_disjoint_octs(double* x, double* y, int count, double dmin, double dmax, int* done) {
  lanes::avx512::Limits l;
  lanes::avx512::set_limits(&l, dmin, dmax);
  const __m512i even = _mm512_set_epi64(14, 12, 10, 8, 6, 4, 2, 0), odd = _mm512_set_epi64(15, 13, 11, 9, 7, 5, 3, 1);
  const __m512i low = _mm512_set_epi64(11, 3, 10, 2, 9, 1, 8, 0), high = _mm512_set_epi64(15, 7, 14, 6, 13, 5, 12, 4);
  int changed = 0, k = 0;
  for (; k + 8 <= count; k += 8) {
    double* px = x + 2 * k;
    double* py = y + 2 * k;
    // Lane s holds spring k + s: the first ends are the even elements, the second ends the odd
    // ones. (Two-source permutes rather than unpacks, whose GCC 12 intrinsics warn.)
    const __m512d xa = _mm512_loadu_pd(px), xb = _mm512_loadu_pd(px + 8);
    const __m512d ya = _mm512_loadu_pd(py), yb = _mm512_loadu_pd(py + 8);
    __m512d xi = _mm512_permutex2var_pd(xa, even, xb), xj = _mm512_permutex2var_pd(xa, odd, xb);
    __m512d yi = _mm512_permutex2var_pd(ya, even, yb), yj = _mm512_permutex2var_pd(ya, odd, yb);
    const unsigned moved = lanes::avx512::constrain_springs(l, &xi, &yi, &xj, &yj);
    if (moved == 0) continue;
    changed += __builtin_popcount(moved);
    _mm512_storeu_pd(px, _mm512_permutex2var_pd(xi, low, xj));
    _mm512_storeu_pd(px + 8, _mm512_permutex2var_pd(xi, high, xj));
    _mm512_storeu_pd(py, _mm512_permutex2var_pd(yi, low, yj));
    _mm512_storeu_pd(py + 8, _mm512_permutex2var_pd(yi, high, yj));
  }
  *done = k;
  return changed;
}
#endif

// Springs (x[2k], x[2k + 1]) for k < count: one half-pass of the red-black order. They share no
// mass, so their order does not matter; eight at a time with AVX-512, then four with AVX, then two
// (the layouts tried instead: bench/README.md, "Constants of the step").
int constrain_disjoint_pairs(double* x, double* y, int count, double dmin, double dmax) {
  int changed = 0, k = 0;
  const int width = vector_width();
#if defined(SOFTDROP_AVX_DISPATCH)
  if (width >= 8) changed = constrain_disjoint_octs(x, y, count, dmin, dmax, &k);
  if (width >= 4 && k + 4 <= count) {
    int quads = 0;
    changed += constrain_disjoint_quads(x + 2 * k, y + 2 * k, count - k, dmin, dmax, &quads);
    k += quads;
  }
  lanes::sse2::Limits l;
  lanes::sse2::set_limits(&l, dmin, dmax);
  for (; width >= 2 && k + 2 <= count; k += 2) {
    double* px = x + 2 * k;
    double* py = y + 2 * k;
    const __m128d xa = _mm_loadu_pd(px), xb = _mm_loadu_pd(px + 2);  // (x_i0, x_j0), (x_i1, x_j1)
    const __m128d ya = _mm_loadu_pd(py), yb = _mm_loadu_pd(py + 2);
    __m128d xi = _mm_unpacklo_pd(xa, xb), xj = _mm_unpackhi_pd(xa, xb);
    __m128d yi = _mm_unpacklo_pd(ya, yb), yj = _mm_unpackhi_pd(ya, yb);
    const unsigned moved = lanes::sse2::bits(lanes::sse2::constrain_springs(l, &xi, &yi, &xj, &yj));
    if (moved == 0) continue;
    changed += static_cast<int>((moved & 1) + (moved >> 1));
    _mm_storeu_pd(px, _mm_unpacklo_pd(xi, xj));
    _mm_storeu_pd(px + 2, _mm_unpackhi_pd(xi, xj));
    _mm_storeu_pd(py, _mm_unpacklo_pd(yi, yj));
    _mm_storeu_pd(py + 2, _mm_unpackhi_pd(yi, yj));
  }
#endif
  for (; k < count; ++k) changed += constrain(x, y, 2 * k, 2 * k + 1, dmin, dmax);
  return changed;
}

// One pass of the red-black order. Springs (0,1), (2,3), ... share no mass, nor do (1,2), (3,4),
// ...: each half-pass is a set of independent corrections. The spring that closes the ring,
// (n-1, 0), is outside the contiguous runs: for an even ring it ends the second half-pass; for an
// odd one it touches the first spring's mass, so it goes last.
int red_black_pass(double* x, double* y, int n, double dmin, double dmax) {
  const int pairs = n / 2;
  int changed = constrain_disjoint_pairs(x, y, pairs, dmin, dmax);
  changed += constrain_disjoint_pairs(x + 1, y + 1, n % 2 == 0 ? pairs - 1 : pairs, dmin, dmax);
  return changed + constrain(x, y, n - 1, 0, dmin, dmax);
}

// Link i of a sequential pass: spring (i, i+1) (or (n-1, 0)), whose first end (xi, yi) is held in
// registers as the previous link left it. Stores mass i, leaves mass i+1 in (xi, yi), and returns 1
// if it moved the ends.
inline int sequential_link(double* x, double* y, int i, int n, double* xi, double* yi, double dmin,
                           double dmax) {
  // The closing spring's far end is mass 0, as the first spring left it.
  const int j = i + 1 == n ? 0 : i + 1;
  double xj = x[j], yj = y[j];
  const int moved = constrain_ends(xi, yi, &xj, &yj, dmin, dmax);
  x[i] = *xi;
  y[i] = *yi;
  *xi = xj;
  *yi = yj;
  return moved;
}

// One pass of the sequential (reference) order, springs (0,1), (1,2), ..., (n-1, 0): each spring
// sees its neighbour's correction, a serial chain of square roots and divisions. The chain is
// latency-bound, so the mass shared with the next spring stays in a register instead of going
// through memory (a store and a reload on every link).
int sequential_pass(double* x, double* y, int n, double dmin, double dmax) {
  int changed = 0;
  double xi = x[0], yi = y[0];
  for (int i = 0; i < n; ++i) changed += sequential_link(x, y, i, n, &xi, &yi, dmin, dmax);
  x[0] = xi;  // the closing spring's correction of mass 0
  y[0] = yi;
  return changed;
}

}  // namespace

int apply_length_constraint(DropletState* state, double rest_length, double max_strain, int iterations,
                            ConstraintOrder order) {
  const int n = state->size();
  const double dmax = (1 + max_strain) * rest_length;
  const double dmin = (1 - max_strain) * rest_length;
  double *x = state->x.data(), *y = state->y.data();
  int corrections = 0;
  for (int pass = 0; pass < iterations; ++pass) {
    int changed = 0;
    if (order == ConstraintOrder::sequential) {
      changed = sequential_pass(x, y, n, dmin, dmax);
    } else {
      changed = red_black_pass(x, y, n, dmin, dmax);
    }
    corrections += changed;
    if (changed == 0) break;
  }
  return corrections;
}

VectorWidth constraint_vector_width() { return static_cast<VectorWidth>(vector_width()); }

VectorWidth limit_constraint_vector_width(VectorWidth width) {
  const int w = static_cast<int>(width);
  if (w != 1 && w != 2 && w != 4 && w != 8)
    throw std::invalid_argument("vector width " + std::to_string(w) + ": must be 1, 2, 4 or 8");
  width_limit.store(w, std::memory_order_relaxed);
  return constraint_vector_width();
}

}  // namespace softdrop
