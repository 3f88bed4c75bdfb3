// The sequential length constraint on many rings at once, each ring a lane of vector registers:
// the same corrections in the same order as apply_length_constraint, so each ring gets the bits it
// would get alone.
#include <algorithm>
#include <type_traits>

#include "lane_layout.hpp"
#include "lane_policy.hpp"
#include "lane_simd.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/droplet.hpp"
#include "spring_correction.hpp"

namespace softdrop {
namespace {

// The interleaved sequential order keeps its rings as lanes of vector registers (a padding lane
// repeats a ring, doing the same work on the same memory): two or four rings to a register with
// SSE2 or AVX (length_constraint_wide_passes.inc, one loop for both), and with AVX-512 the lane-by-lane
// constraint of the block on a copy laid out lane by lane.
#if defined(SOFTDROP_AVX_DISPATCH)
// Two rings per SSE2 register.
namespace pairs {
using namespace lanes::x2_sse2;
inline void load_lanes(double* const* x, int base, int i, V* v) {
  *v = _mm_loadh_pd(_mm_load_sd(x[base] + i), x[base + 1] + i);
}
inline void store_lanes(double* const* x, int base, int i, const V& v) {
  _mm_storel_pd(x[base] + i, v);
  _mm_storeh_pd(x[base + 1] + i, v);
}
#define SOFTDROP_LANE_TARGET
#include "length_constraint_wide_passes.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace pairs

// Four rings per AVX register.
namespace quads {
using namespace lanes::x4_avx;
SOFTDROP_AVX inline void load_lanes(double* const* x, int base, int i, V* v) {
  *v = _mm256_set_pd(x[base + 3][i], x[base + 2][i], x[base + 1][i], x[base][i]);
}
SOFTDROP_AVX inline void store_lanes(double* const* x, int base, int i, const V& v) {
  const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1);
  _mm_storel_pd(x[base] + i, lo);
  _mm_storeh_pd(x[base + 1] + i, lo);
  _mm_storel_pd(x[base + 2] + i, hi);
  _mm_storeh_pd(x[base + 3] + i, hi);
}
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX
#include "length_constraint_wide_passes.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace quads
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
    case 3:
      passes(std::integral_constant<int, 3>{}, x, y, counts);
      break;
    case 2:
      passes(std::integral_constant<int, 2>{}, x, y, counts);
      break;
    default:
      passes(std::integral_constant<int, 1>{}, x, y, counts);
      break;
  }
  for (int t = 0; t < same; ++t) corrections[t] = counts[t];
}

}  // namespace

void apply_length_constraint_interleaved(DropletState* const* rings, int count, double rest_length, double max_strain,
                                         int iterations, int* corrections) {
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
        quads::sequential_passes<decltype(k)::value>(x, y, n, iterations, dmin, dmax, counts);
      });
      r += same;
      continue;
    }
#endif
#if defined(SOFTDROP_AVX_DISPATCH)
    sequential_rings<2>(rings + r, same, corrections + r, [&](auto k, double** x, double** y, int* counts) {
      pairs::sequential_passes<decltype(k)::value>(x, y, n, iterations, dmin, dmax, counts);
    });
#endif
    r += same;
  }
}

}  // namespace softdrop
