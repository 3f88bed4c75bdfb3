#include "softdrop/droplet.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "lane_layout.hpp"
#include "lane_simd.hpp"
#include "simd_dispatch.hpp"
#include "validation.hpp"

namespace softdrop {
using detail::fail;
using detail::num;
namespace {
bool positive(double v) { return std::isfinite(v) && v > 0; }

// Orientation sign of (a, b, c).
double cross(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}
}  // namespace

double DropletParams::rest_length() const {
  return 2 * radius * std::sin(M_PI / masses) / (1 + max_strain);
}

double DropletParams::inflated_area() const {
  return 0.5 * masses * radius * radius * std::sin(2 * M_PI / masses);
}

bool DropletParams::IsValid(std::string* why) const {
  if (masses < 8 || masses > 100000)
    return fail(why, "masses = " + std::to_string(masses) + ": must be in [8, 100000]");
  if (!positive(mass)) return fail(why, "mass = " + num(mass) + ": must be > 0");
  if (!positive(radius)) return fail(why, "radius = " + num(radius) + ": must be > 0");
  if (!positive(nrt)) return fail(why, "nrt = " + num(nrt) + ": must be > 0");
  if (!std::isfinite(ks) || ks < 0) return fail(why, "ks = " + num(ks) + ": must be >= 0");
  if (!std::isfinite(kd) || kd < 0) return fail(why, "kd = " + num(kd) + ": must be >= 0");
  if (!positive(kc)) return fail(why, "kc = " + num(kc) + ": must be > 0");
  if (!std::isfinite(cc) || cc < 0) return fail(why, "cc = " + num(cc) + ": must be >= 0");
  if (!std::isfinite(gravity)) return fail(why, "gravity = " + num(gravity) + ": must be finite");
  if (!positive(dt) || dt > 1e-2) return fail(why, "dt = " + num(dt) + ": must be in (0, 0.01]");
  if (!std::isfinite(max_strain) || max_strain <= 0 || max_strain >= 0.5)
    return fail(why, "max-strain = " + num(max_strain) + ": must be in (0, 0.5)");
  if (constraint_iterations < 0 || constraint_iterations > 100)
    return fail(why, "constraint-iterations = " + std::to_string(constraint_iterations) +
                         ": must be in [0, 100]");
  if (!std::isfinite(max_depth) || max_depth <= 0)
    return fail(why, "max-depth = " + num(max_depth) + ": must be > 0");
  if (!std::isfinite(viscosity) || viscosity < 0)
    return fail(why, "viscosity = " + num(viscosity) + ": must be >= 0");
  if (viscosity * dt > 0.5)  // names both, since either may be the one the user changed
    return fail(why, "viscosity = " + num(viscosity) + ", dt = " + num(dt) + ": viscosity * dt = " +
                         num(viscosity * dt) + " must be <= 0.5");
  // Explicit integration is only stable when the stiffest oscillator is resolved in time.
  const double omega_dt = std::sqrt(std::max(ks, kc) / mass) * dt;
  if (omega_dt > 0.5)
    return fail(why, "dt = " + num(dt) + ": too large for the stiffness, sqrt(max(ks, kc) / mass) * dt = " +
                         num(omega_dt) + " must be <= 0.5");
  if (std::max(kd, cc) * dt / mass > 1.0)
    return fail(why, "dt = " + num(dt) + ": too large for the damping, max(kd, cc) * dt / mass = " +
                         num(std::max(kd, cc) * dt / mass) + " must be <= 1");
  return true;
}

void DropletState::resize(int n) {
  for (auto* v : {&x, &y, &px, &py, &fx, &fy}) v->assign(static_cast<std::size_t>(n), 0.0);
}

void place_droplet(const DropletParams& params, double cx, double cy, DropletState* state) {
  state->resize(params.masses);
  for (int i = 0; i < params.masses; ++i) {
    const double a = 2 * M_PI * i / params.masses;
    state->x[i] = state->px[i] = cx + params.radius * std::cos(a);
    state->y[i] = state->py[i] = cy + params.radius * std::sin(a);
  }
}

ConstraintOrder parse_constraint_order(const std::string& name) {
  if (name == "sequential") return ConstraintOrder::sequential;
  if (name == "red-black") return ConstraintOrder::red_black;
  throw std::invalid_argument("constraint-order '" + name + "': expected sequential or red-black");
}

const char* to_string(ConstraintOrder order) {
  return order == ConstraintOrder::sequential ? "sequential" : "red-black";
}

namespace {

// Brings the spring between (xi, yi) and (xj, yj) back inside [dmin, dmax]; returns 1 if it moved
// its ends.
inline int constrain_ends(double* xi, double* yi, double* xj, double* yj, double dmin, double dmax) {
  const double dx = *xj - *xi, dy = *yj - *yi;
  const double d2 = dx * dx + dy * dy, dmax2 = dmax * dmax;
  if (d2 <= dmax2 && d2 >= dmin * dmin) return 0;
  const double d = std::sqrt(d2);
  if (d == 0) return 0;
  // Stretched or compressed is decided on d2, as the test above was: a d2 just above dmax^2 can
  // have a square root that rounds to dmax, and "d > dmax" would then call it compressed and pull
  // the spring down to dmin.
  const double target = d2 > dmax2 ? dmax : dmin;
  // > 0 pulls the ends together, < 0 pushes apart. (d - target) / (d + d) is 0.5 (d - target) / d
  // to the bit (halving and doubling are exact), with the halving off the chain of dependent
  // operations.
  const double c = (d - target) / (d + d);
  *xi += c * dx;
  *yi += c * dy;
  *xj -= c * dx;
  *yj -= c * dy;
  return 1;
}

inline int constrain(double* x, double* y, int i, int j, double dmin, double dmax) {
  return constrain_ends(x + i, y + i, x + j, y + j, dmin, dmax);
}

#if defined(__SSE2__)
// Two springs at once, lane by lane the operations of constrain_ends() in the same order on the
// same values, so the bits are those of the scalar code. Returns the lanes whose spring moved, as
// _mm_movemask_pd gives them (bit 0: low lane, bit 1: high lane).
struct PairLimits {
  __m128d dmax = {}, dmin = {}, dmax2 = {}, dmin2 = {};
  PairLimits(double lo, double hi)
      : dmax(_mm_set1_pd(hi)), dmin(_mm_set1_pd(lo)), dmax2(_mm_set1_pd(hi * hi)), dmin2(_mm_set1_pd(lo * lo)) {}
};
inline int constrain_two(const PairLimits& l, __m128d* xi, __m128d* yi, __m128d* xj, __m128d* yj) {
  const __m128d dx = _mm_sub_pd(*xj, *xi), dy = _mm_sub_pd(*yj, *yi);
  const __m128d d2 = _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
  // Out of limits (NaN included, as in the scalar test) and not of zero length.
  const __m128d inside = _mm_and_pd(_mm_cmple_pd(d2, l.dmax2), _mm_cmpge_pd(d2, l.dmin2));
  const __m128d out = _mm_andnot_pd(inside, _mm_cmpneq_pd(d2, _mm_setzero_pd()));
  const int mask = _mm_movemask_pd(out);
  if (mask == 0) return 0;
  const __m128d d = _mm_sqrt_pd(d2);
  const __m128d longer = _mm_cmpgt_pd(d2, l.dmax2);
  const __m128d target = _mm_or_pd(_mm_and_pd(longer, l.dmax), _mm_andnot_pd(longer, l.dmin));
  const __m128d c = _mm_div_pd(_mm_sub_pd(d, target), _mm_add_pd(d, d));
  const __m128d cx = _mm_and_pd(out, _mm_mul_pd(c, dx)), cy = _mm_and_pd(out, _mm_mul_pd(c, dy));
  // Lanes in limits add -0 and subtract +0, which leave every double (-0 included) as it is.
  const __m128d keep = _mm_andnot_pd(out, _mm_set1_pd(-0.0));
  *xi = _mm_add_pd(*xi, _mm_or_pd(cx, keep));
  *yi = _mm_add_pd(*yi, _mm_or_pd(cy, keep));
  *xj = _mm_sub_pd(*xj, cx);
  *yj = _mm_sub_pd(*yj, cy);
  return mask;
}
#endif

// The vector width in use: the processor's widest, unless narrowed by
// limit_constraint_vector_width.
int machine_width() {
#if defined(SOFTDROP_AVX_DISPATCH)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return 8;
  if (__builtin_cpu_supports("avx")) return 4;
#endif
#if defined(__SSE2__)
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
// Four and eight springs at once (lane_simd.hpp), shared with the lane-by-lane step.
using lanes::avx::constrain_four;
using lanes::avx::QuadLimits;
using lanes::avx::set_quad_limits;
using lanes::avx512::constrain_eight;
using lanes::avx512::OctLimits;
using lanes::avx512::set_oct_limits;

// The red-black half-pass four springs at a time, from spring 0 while four remain; returns the
// corrections and sets *done to the springs it did.
SOFTDROP_AVX int constrain_disjoint_quads(double* x, double* y, int count, double dmin, double dmax, int* done) {
  QuadLimits l;
  set_quad_limits(&l, dmin, dmax);
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
    const int moved = constrain_four(l, &xi, &yi, &xj, &yj);
    if (moved == 0) continue;
    changed += __builtin_popcount(static_cast<unsigned>(moved));
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
  OctLimits l;
  set_oct_limits(&l, dmin, dmax);
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
    const unsigned moved = constrain_eight(l, &xi, &yi, &xj, &yj);
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
#endif
#if defined(__SSE2__)
  const PairLimits l(dmin, dmax);
  for (; width >= 2 && k + 2 <= count; k += 2) {
    double* px = x + 2 * k;
    double* py = y + 2 * k;
    const __m128d xa = _mm_loadu_pd(px), xb = _mm_loadu_pd(px + 2);  // (x_i0, x_j0), (x_i1, x_j1)
    const __m128d ya = _mm_loadu_pd(py), yb = _mm_loadu_pd(py + 2);
    __m128d xi = _mm_unpacklo_pd(xa, xb), xj = _mm_unpackhi_pd(xa, xb);
    __m128d yi = _mm_unpacklo_pd(ya, yb), yj = _mm_unpackhi_pd(ya, yb);
    const int moved = constrain_two(l, &xi, &yi, &xj, &yj);
    if (moved == 0) continue;
    changed += (moved & 1) + (moved >> 1);
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

namespace {
// The interleaved sequential order keeps its rings as lanes of vector registers: lane l of
// register r is ring kLanes r + l, with x[kLanes r + l] and y[...] that ring's arrays. A padding
// lane repeats a ring, doing the same work on the same memory. Each lane does sequential_link()'s
// operations on its own ring, K registers' chains side by side. Passes go on until no ring
// changes; a pass that changes nothing changes nothing again, so the extra passes of a ring that
// has stopped keep its bits. counts[ring] gets the ring's corrections. The SSE2, AVX and AVX-512
// versions below are the same loop on three vector types (an AVX or AVX-512 body must be compiled
// apart, for that instruction set only); the AVX-512 one works on a copy laid out lane by lane.
#if defined(__SSE2__)
inline void load_lanes(double* const* x, int base, int i, __m128d* v) {
  *v = _mm_loadh_pd(_mm_load_sd(x[base] + i), x[base + 1] + i);
}
inline void store_lanes(double* const* x, int base, int i, const __m128d& v) {
  _mm_storel_pd(x[base] + i, v);
  _mm_storeh_pd(x[base + 1] + i, v);
}

// Two rings per SSE2 register.
template <int K>
void sequential_passes_paired(double* const* x, double* const* y, int n, int iterations, double dmin, double dmax,
                              int* counts) {
  const PairLimits l(dmin, dmax);
  bool active[K];
  for (int r = 0; r < K; ++r) active[r] = true;
  for (int t = 0; t < 2 * K; ++t) counts[t] = 0;
  for (int pass = 0; pass < iterations; ++pass) {
    __m128d xi[K], yi[K];
    int changed[2 * K] = {};
    for (int r = 0; r < K; ++r) {
      load_lanes(x, 2 * r, 0, &xi[r]);
      load_lanes(y, 2 * r, 0, &yi[r]);
    }
    for (int i = 0; i < n; ++i) {
      const int j = i + 1 == n ? 0 : i + 1;
      for (int r = 0; r < K; ++r) {
        if (!active[r]) continue;
        __m128d xj, yj;
        load_lanes(x, 2 * r, j, &xj);
        load_lanes(y, 2 * r, j, &yj);
        const int moved = constrain_two(l, &xi[r], &yi[r], &xj, &yj);
        changed[2 * r] += moved & 1;
        changed[2 * r + 1] += moved >> 1;
        store_lanes(x, 2 * r, i, xi[r]);
        store_lanes(y, 2 * r, i, yi[r]);
        xi[r] = xj;
        yi[r] = yj;
      }
    }
    bool any = false;
    for (int r = 0; r < K; ++r) {
      if (!active[r]) continue;
      store_lanes(x, 2 * r, 0, xi[r]);  // the closing spring's correction of mass 0
      store_lanes(y, 2 * r, 0, yi[r]);
      counts[2 * r] += changed[2 * r];
      counts[2 * r + 1] += changed[2 * r + 1];
      active[r] = changed[2 * r] + changed[2 * r + 1] != 0;
      any = any || active[r];
    }
    if (!any) break;
  }
}
#endif
#if defined(SOFTDROP_AVX_DISPATCH)
SOFTDROP_AVX inline void load_lanes(double* const* x, int base, int i, __m256d* v) {
  *v = _mm256_set_pd(x[base + 3][i], x[base + 2][i], x[base + 1][i], x[base][i]);
}
SOFTDROP_AVX inline void store_lanes(double* const* x, int base, int i, const __m256d& v) {
  const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1);
  _mm_storel_pd(x[base] + i, lo);
  _mm_storeh_pd(x[base + 1] + i, lo);
  _mm_storel_pd(x[base + 2] + i, hi);
  _mm_storeh_pd(x[base + 3] + i, hi);
}

// Four rings per AVX register.
template <int K>
SOFTDROP_AVX void sequential_passes_quad(double* const* x, double* const* y, int n, int iterations, double dmin,
                                         double dmax, int* counts) {
  QuadLimits l;
  set_quad_limits(&l, dmin, dmax);
  bool active[K];
  for (int r = 0; r < K; ++r) active[r] = true;
  for (int t = 0; t < 4 * K; ++t) counts[t] = 0;
  for (int pass = 0; pass < iterations; ++pass) {
    __m256d xi[K], yi[K];
    int changed[4 * K] = {};
    for (int r = 0; r < K; ++r) {
      load_lanes(x, 4 * r, 0, &xi[r]);
      load_lanes(y, 4 * r, 0, &yi[r]);
    }
    for (int i = 0; i < n; ++i) {
      const int j = i + 1 == n ? 0 : i + 1;
      for (int r = 0; r < K; ++r) {
        if (!active[r]) continue;
        __m256d xj, yj;
        load_lanes(x, 4 * r, j, &xj);
        load_lanes(y, 4 * r, j, &yj);
        const int moved = constrain_four(l, &xi[r], &yi[r], &xj, &yj);
        for (int b = 0; b < 4; ++b) changed[4 * r + b] += (moved >> b) & 1;
        store_lanes(x, 4 * r, i, xi[r]);
        store_lanes(y, 4 * r, i, yi[r]);
        xi[r] = xj;
        yi[r] = yj;
      }
    }
    bool any = false;
    for (int r = 0; r < K; ++r) {
      if (!active[r]) continue;
      store_lanes(x, 4 * r, 0, xi[r]);  // the closing spring's correction of mass 0
      store_lanes(y, 4 * r, 0, yi[r]);
      int sum = 0;
      for (int b = 0; b < 4; ++b) counts[4 * r + b] += changed[4 * r + b], sum += changed[4 * r + b];
      active[r] = sum != 0;
      any = any || active[r];
    }
    if (!any) break;
  }
}
#endif

#if defined(SOFTDROP_AVX_DISPATCH)
// The lane-by-lane sequential constraint (lanes::constrain_sequential) on a copy of the rings
// x[0..8K), y[...] laid out lane by lane.
template <int K>
void sequential_passes_oct(double* const* x, double* const* y, int n, int iterations, double dmin, double dmax,
                           int* counts) {
  const std::size_t size = static_cast<std::size_t>(n) * 8 * K;
  double* const X = lanes::step_scratch(2 * size);
  double* const Y = X + size;
  lanes::copy_in(x, X, n, K);
  lanes::copy_in(y, Y, n, K);
  lanes::constrain_sequential(X, Y, n, K, iterations, dmin, dmax, counts);
  lanes::copy_out(x, X, n, K);
  lanes::copy_out(y, Y, n, K);
}
#endif

// Rings [0, same) of one size (same <= 3 kLanes) as lanes, kLanes per register, padded with the
// last ring; passes(registers, x, y, counts) runs them, with registers a std::integral_constant.
template <int kLanes, class Passes>
void sequential_rings(DropletState* const* rings, int same, int* corrections, const Passes& passes) {
  const int registers = (same + kLanes - 1) / kLanes;
  double *x[3 * kLanes], *y[3 * kLanes];
  int counts[3 * kLanes];
  for (int t = 0; t < kLanes * registers; ++t) {
    DropletState* ring = rings[std::min(t, same - 1)];
    x[t] = ring->x.data();
    y[t] = ring->y.data();
  }
  switch (registers) {
    case 3: passes(std::integral_constant<int, 3>{}, x, y, counts); break;
    case 2: passes(std::integral_constant<int, 2>{}, x, y, counts); break;
    default: passes(std::integral_constant<int, 1>{}, x, y, counts); break;
  }
  for (int t = 0; t < same; ++t) corrections[t] = counts[t];
}

}  // namespace

int interleaved_ring_capacity() {
  const int width = vector_width();
  return width >= 8 ? 24 : width >= 4 ? 12 : width >= 2 ? 6 : 1;
}

void apply_length_constraint_interleaved(DropletState* const* rings, int count, double rest_length,
                                         double max_strain, int iterations, int* corrections) {
  const double dmax = (1 + max_strain) * rest_length;
  const double dmin = (1 - max_strain) * rest_length;
  const int width = vector_width(), capacity = interleaved_ring_capacity();
  int r = 0;
  while (r < count) {
    const int n = rings[r]->size();
    int same = 1;  // rings of one size go together: a lane each, up to 3 registers side by side
    while (same < capacity && r + same < count && rings[r + same]->size() == n) ++same;
    if (width == 1) {
      corrections[r] = apply_length_constraint(rings[r], rest_length, max_strain, iterations);
      r += same;
      continue;
    }
#if defined(SOFTDROP_AVX_DISPATCH)
    if (width >= 8) {
      sequential_rings<8>(rings + r, same, corrections + r, [&](auto k, double** x, double** y, int* counts) {
        sequential_passes_oct<decltype(k)::value>(x, y, n, iterations, dmin, dmax, counts);
      });
      r += same;
      continue;
    }
    if (width >= 4) {
      sequential_rings<4>(rings + r, same, corrections + r, [&](auto k, double** x, double** y, int* counts) {
        sequential_passes_quad<decltype(k)::value>(x, y, n, iterations, dmin, dmax, counts);
      });
      r += same;
      continue;
    }
#endif
#if defined(__SSE2__)
    sequential_rings<2>(rings + r, same, corrections + r, [&](auto k, double** x, double** y, int* counts) {
      sequential_passes_paired<decltype(k)::value>(x, y, n, iterations, dmin, dmax, counts);
    });
#endif
    r += same;
  }
}


VectorWidth constraint_vector_width() { return static_cast<VectorWidth>(vector_width()); }

VectorWidth limit_constraint_vector_width(VectorWidth width) {
  const int w = static_cast<int>(width);
  if (w != 1 && w != 2 && w != 4 && w != 8)
    throw std::invalid_argument("vector width " + std::to_string(w) + ": must be 1, 2, 4 or 8");
  width_limit.store(w, std::memory_order_relaxed);
  return constraint_vector_width();
}

double ring_area(const DropletState& s) {
  const int n = s.size();
  double twice = 0;
  for (int i = 0, j = n - 1; i < n; j = i++) twice += s.x[j] * s.y[i] - s.x[i] * s.y[j];
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
    return _mm256_and_pd(sides, _mm256_and_pd(_mm256_cmp_pd(d, zero, _CMP_NEQ_UQ), _mm256_cmp_pd(e, zero, _CMP_NEQ_UQ)));
  };
  int j = first;
  for (; j + 4 <= last; j += 4) {
    const __m256d cx = _mm256_loadu_pd(x + j), cy = _mm256_loadu_pd(y + j);
    const __m256d dx = _mm256_loadu_pd(x + j + 1), dy = _mm256_loadu_pd(y + j + 1);
    // cross(a, b, c) and cross(a, b, d)
    const __m256d d1 = _mm256_sub_pd(_mm256_mul_pd(ux, _mm256_sub_pd(cy, Ay)), _mm256_mul_pd(uy, _mm256_sub_pd(cx, Ax)));
    const __m256d d2 = _mm256_sub_pd(_mm256_mul_pd(ux, _mm256_sub_pd(dy, Ay)), _mm256_mul_pd(uy, _mm256_sub_pd(dx, Ax)));
    const __m256d across = opposite(d1, d2);
    if (_mm256_movemask_pd(across) == 0) continue;
    // cross(c, d, a) and cross(c, d, b)
    const __m256d vx = _mm256_sub_pd(dx, cx), vy = _mm256_sub_pd(dy, cy);
    const __m256d d3 = _mm256_sub_pd(_mm256_mul_pd(vx, _mm256_sub_pd(Ay, cy)), _mm256_mul_pd(vy, _mm256_sub_pd(Ax, cx)));
    const __m256d d4 = _mm256_sub_pd(_mm256_mul_pd(vx, _mm256_sub_pd(By, cy)), _mm256_mul_pd(vy, _mm256_sub_pd(Bx, cx)));
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
  const bool four = vector_width() >= 4;
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
    if ((s.y[i] > py) != (s.y[j] > py) &&
        px < (s.x[j] - s.x[i]) * (py - s.y[i]) / (s.y[j] - s.y[i]) + s.x[i])
      inside = !inside;
  }
  return inside;
}

}  // namespace softdrop
