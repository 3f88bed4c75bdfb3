// The length constraint on one ring: passes of single-spring corrections (spring_correction.hpp)
// in the sequential or the red-black order, and the choice of vector width for every constraint.
#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

#include "lane_simd.hpp"
#include "ring_stages.hpp"
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
// Read several times a step by every stage on every thread, written only by
// limit_constraint_vector_width: padded to a whole cache line, so that no variable another thread
// writes at every step can share its line and make each read a cache miss.
struct alignas(64) WidthLimit {
  std::atomic<int> value{8};
};
WidthLimit width_limit;
int vector_width() {
  static const int machine = machine_width();
  return std::min(machine, width_limit.value.load(std::memory_order_relaxed));
}

#if defined(SOFTDROP_AVX_DISPATCH)
// The red-black half-pass two, four and eight springs at a time (length_constraint_half_pass.inc), the
// correction being the kernel of lane_simd.hpp (length_constraint_kernel.inc) shared with the lane-by-lane
// step. Only the split of kWidth interleaved pairs of ends into two registers is per width.
namespace two_lanes {
using namespace lanes::x2_sse2;
// (x_i0, x_j0), (x_i1, x_j1) -> (x_i0, x_i1), (x_j0, x_j1) and back.
inline void load_ends(const double* p, V* i, V* j) {
  const V a = _mm_loadu_pd(p), b = _mm_loadu_pd(p + 2);
  *i = _mm_unpacklo_pd(a, b);
  *j = _mm_unpackhi_pd(a, b);
}
inline void store_ends(double* p, V i, V j) {
  _mm_storeu_pd(p, _mm_unpacklo_pd(i, j));
  _mm_storeu_pd(p + 2, _mm_unpackhi_pd(i, j));
}
#define SOFTDROP_LANE_TARGET
#include "length_constraint_half_pass.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace two_lanes

namespace four_lanes {
using namespace lanes::x4_avx;
// (x_i0 x_j0 | x_i1 x_j1), (x_i2 x_j2 | x_i3 x_j3): unpacking works within 128-bit halves, so the
// lanes hold springs (0, 2 | 1, 3), and unpacking back restores the layout.
SOFTDROP_AVX inline void load_ends(const double* p, V* i, V* j) {
  const V a = _mm256_loadu_pd(p), b = _mm256_loadu_pd(p + 4);
  *i = _mm256_unpacklo_pd(a, b);
  *j = _mm256_unpackhi_pd(a, b);
}
SOFTDROP_AVX inline void store_ends(double* p, V i, V j) {
  _mm256_storeu_pd(p, _mm256_unpacklo_pd(i, j));
  _mm256_storeu_pd(p + 4, _mm256_unpackhi_pd(i, j));
}
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX
#include "length_constraint_half_pass.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace four_lanes

namespace eight_lanes {
using namespace lanes::x8_avx512;
// Lane s holds spring k + s: the first ends are the even elements, the second ends the odd ones.
// (Two-source permutes rather than unpacks, whose GCC 12 intrinsics warn.)
SOFTDROP_AVX512 inline void load_ends(const double* p, V* i, V* j) {
  const V a = _mm512_loadu_pd(p), b = _mm512_loadu_pd(p + 8);
  *i = _mm512_permutex2var_pd(a, _mm512_set_epi64(14, 12, 10, 8, 6, 4, 2, 0), b);
  *j = _mm512_permutex2var_pd(a, _mm512_set_epi64(15, 13, 11, 9, 7, 5, 3, 1), b);
}
SOFTDROP_AVX512 inline void store_ends(double* p, V i, V j) {
  _mm512_storeu_pd(p, _mm512_permutex2var_pd(i, _mm512_set_epi64(11, 3, 10, 2, 9, 1, 8, 0), j));
  _mm512_storeu_pd(p + 8, _mm512_permutex2var_pd(i, _mm512_set_epi64(15, 7, 14, 6, 13, 5, 12, 4), j));
}
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX512
#include "lane_policy.hpp"
#include "length_constraint_half_pass.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace eight_lanes
#endif

// Springs (x[2k], x[2k + 1]) for k < count: one half-pass of the red-black order. They share no
// mass, so their order does not matter; eight at a time with AVX-512, then four with AVX, then two
// (the layouts tried instead: bench/README.md, "Constants of the step").
int constrain_disjoint_pairs(double* x, double* y, int count, double dmin, double dmax) {
  int changed = 0, k = 0;
  const int width = vector_width();
#if defined(SOFTDROP_AVX_DISPATCH)
  int done = 0;
  if (width >= 8) changed += eight_lanes::constrain_disjoint(x, y, count, dmin, dmax, &done), k += done;
  if (width >= 4)
    changed += four_lanes::constrain_disjoint(x + 2 * k, y + 2 * k, count - k, dmin, dmax, &done), k += done;
  if (width >= 2)
    changed += two_lanes::constrain_disjoint(x + 2 * k, y + 2 * k, count - k, dmin, dmax, &done), k += done;
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
inline int sequential_link(double* x, double* y, int i, int n, double* xi, double* yi, double dmin, double dmax) {
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
  width_limit.value.store(w, std::memory_order_relaxed);
  return constraint_vector_width();
}

void constraint_stage(const DropletModel& m, DropletRuntime& r) {
  r.changed();
  apply_length_constraint(&r.state, m.context.rest_length, m.params.max_strain, m.params.constraint_iterations,
                          m.params.constraint_order);
}

}  // namespace softdrop
