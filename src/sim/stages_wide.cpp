// The stages of a step on rings laid out lane by lane (lane_layout.hpp), eight rings to a group,
// for AVX-512 (a group is one register) and AVX (two): the kernels of lane_kernels.inc (and of the
// stage_kernels.inc it includes), compiled once for each, and the copies between the rings and the
// layout (AVX 4 x 4 transposes, for both).

#include <cstddef>
#include <vector>

#include "lane_layout.hpp"
#include "lane_simd.hpp"
#include "softdrop/droplet.hpp"

namespace softdrop::lanes {

#if defined(SOFTDROP_AVX_DISPATCH)
namespace x8_avx {
namespace {

// Transposes the 4 x 4 block of doubles m[0..3] (m[t][c] -> m[c][t]).
SOFTDROP_AVX inline void transpose4(__m256d* m) {
  const __m256d a0 = _mm256_unpacklo_pd(m[0], m[1]), a1 = _mm256_unpackhi_pd(m[0], m[1]);  // (0, 2), (1, 3)
  const __m256d a2 = _mm256_unpacklo_pd(m[2], m[3]), a3 = _mm256_unpackhi_pd(m[2], m[3]);
  m[0] = _mm256_permute2f128_pd(a0, a2, 0x20);
  m[1] = _mm256_permute2f128_pd(a1, a3, 0x20);
  m[2] = _mm256_permute2f128_pd(a0, a2, 0x31);
  m[3] = _mm256_permute2f128_pd(a1, a3, 0x31);
}

// Copies masses [0, n) of rings x[0..L) into X[i L + t] (in; with Add, adds them: X[i L + t] +
// x[t][i]) or back (out, skipping a null ring, and first moving what the ring held to previous[t]
// when that is given), four by four.
template <int L, bool In, bool Add = false>
SOFTDROP_AVX void transpose_rings(double* const* x, double* X, int n, double* const* previous = nullptr) {
  static_assert(In || !Add);
  int i = 0;
  for (; i + 4 <= n; i += 4)
    for (int g = 0; g < L; g += 4) {
      __m256d m[4];
      for (int t = 0; t < 4; ++t)
        m[t] = In ? _mm256_loadu_pd(x[g + t] + i) : _mm256_loadu_pd(X + static_cast<std::ptrdiff_t>(i + t) * L + g);
      transpose4(m);
      for (int t = 0; t < 4; ++t) {
        double* const to = X + static_cast<std::ptrdiff_t>(i + t) * L + g;
        if (Add) {
          _mm256_storeu_pd(to, _mm256_add_pd(_mm256_loadu_pd(to), m[t]));
        } else if (In) {
          _mm256_storeu_pd(to, m[t]);
        } else if (x[g + t]) {
          if (previous) _mm256_storeu_pd(previous[g + t] + i, _mm256_loadu_pd(x[g + t] + i));
          _mm256_storeu_pd(x[g + t] + i, m[t]);
        }
      }
    }
  for (; i < n; ++i)
    for (int t = 0; t < L; ++t) {
      if (Add) {
        X[i * L + t] += x[t][i];
      } else if (In) {
        X[i * L + t] = x[t][i];
      } else if (x[t]) {
        if (previous) previous[t][i] = x[t][i];
        x[t][i] = X[i * L + t];
      }
    }
}

#define SOFTDROP_LANE_TARGET SOFTDROP_AVX
#include "lane_kernels.inc"
#undef SOFTDROP_LANE_TARGET

}  // namespace
}  // namespace x8_avx

namespace x8_avx512 {
namespace {

// The copies of the AVX code (four by four), which bench_stages BM_LaneCopies measures faster than
// 8 x 8 transposes with two-source permutes (bench/README.md, "Constants of the step").
using x8_avx::transpose_rings;

#define SOFTDROP_LANE_TARGET SOFTDROP_AVX512
#include "lane_kernels.inc"
#undef SOFTDROP_LANE_TARGET

}  // namespace
}  // namespace x8_avx512

void copy_in(double* const* rings, double* X, int n, int registers) {
  if (avx512_in_use())
    x8_avx512::copy_in(rings, X, n, registers);
  else
    x8_avx::copy_in(rings, X, n, registers);
}
void add_in(const double* const* rings, double* X, int n, int registers) {
  if (avx512_in_use())
    x8_avx512::add_in(rings, X, n, registers);
  else
    x8_avx::add_in(rings, X, n, registers);
}
void copy_out(double* const* rings, const double* X, int n, int registers, double* const* previous) {
  if (avx512_in_use())
    x8_avx512::copy_out(rings, X, n, registers, previous);
  else
    x8_avx::copy_out(rings, X, n, registers, previous);
}
void constrain_sequential(double* X, double* Y, int n, int registers, int iterations, double dmin, double dmax,
                          int* counts) {
  if (avx512_in_use())
    x8_avx512::constrain_sequential(X, Y, n, registers, iterations, dmin, dmax, counts);
  else
    x8_avx::constrain_sequential(X, Y, n, registers, iterations, dmin, dmax, counts);
}
void constrain_red_black(double* X, double* Y, int n, int registers, int iterations, double dmin, double dmax,
                         int* counts) {
  if (avx512_in_use())
    x8_avx512::constrain_red_black(X, Y, n, registers, iterations, dmin, dmax, counts);
  else
    x8_avx::constrain_red_black(X, Y, n, registers, iterations, dmin, dmax, counts);
}
void forces_before_contacts(const StepContext& k, const double* X, const double* Y, const double* PX, const double* PY,
                            double* FX, double* FY, double* area, int n, int registers) {
  if (avx512_in_use())
    x8_avx512::forces_before_contacts(k, X, Y, PX, PY, FX, FY, area, n, registers);
  else
    x8_avx::forces_before_contacts(k, X, Y, PX, PY, FX, FY, area, n, registers);
}
void ring_spring_forces(const StepContext& k, const double* x, const double* y, const double* px, const double* py,
                        int n, double* plus_x, double* plus_y, double* minus_x, double* minus_y) {
  if (avx512_in_use())
    x8_avx512::ring_spring_forces(k, x, y, px, py, n, plus_x, plus_y, minus_x, minus_y);
  else
    x8_avx::ring_spring_forces(k, x, y, px, py, n, plus_x, plus_y, minus_x, minus_y);
}
void viscosity(const StepContext& k, const double* X, const double* Y, const double* PX, const double* PY, double* FX,
               double* FY, int n, int registers) {
  if (avx512_in_use())
    x8_avx512::viscosity(k, X, Y, PX, PY, FX, FY, n, registers);
  else
    x8_avx::viscosity(k, X, Y, PX, PY, FX, FY, n, registers);
}
void centres(const double* X, const double* Y, int n, int registers, double* cx, double* cy) {
  if (avx512_in_use())
    x8_avx512::centres(X, Y, n, registers, cx, cy);
  else
    x8_avx::centres(X, Y, n, registers, cx, cy);
}
void integrate(double h2m, double* X, double* Y, double* PX, double* PY, const double* FX, const double* FY, int n,
               int registers) {
  if (avx512_in_use())
    x8_avx512::integrate(h2m, X, Y, PX, PY, FX, FY, n, registers);
  else
    x8_avx::integrate(h2m, X, Y, PX, PY, FX, FY, n, registers);
}
#endif

double* step_scratch(std::size_t doubles) {
  thread_local std::vector<double> scratch;
  if (scratch.size() < doubles) scratch.resize(doubles);
  return scratch.data();
}

}  // namespace softdrop::lanes
