// The sequential length constraint on many rings at once, each ring a lane of vector registers:
// the same corrections in the same order as apply_length_constraint, so each ring gets the bits it
// would get alone.
#include <algorithm>
#include <type_traits>

#include "lane_layout.hpp"
#include "lane_simd.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/droplet.hpp"
#include "spring_correction.hpp"

namespace softdrop {
#if defined(__SSE2__)
using constraint_detail::constrain_two;
using constraint_detail::PairLimits;
#endif
namespace {
#if defined(SOFTDROP_AVX_DISPATCH)
using lanes::avx::constrain_four;
using lanes::avx::QuadLimits;
using lanes::avx::set_quad_limits;
#endif

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
  const int width = static_cast<int>(constraint_vector_width());
  return width >= 8 ? 24 : width >= 4 ? 12 : width >= 2 ? 6 : 1;
}

void apply_length_constraint_interleaved(DropletState* const* rings, int count, double rest_length,
                                         double max_strain, int iterations, int* corrections) {
  const double dmax = (1 + max_strain) * rest_length;
  const double dmin = (1 - max_strain) * rest_length;
  const int width = static_cast<int>(constraint_vector_width()), capacity = interleaved_ring_capacity();
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


}  // namespace softdrop
