// The force and integration stages of a step on rings laid out lane by lane (lane_layout.hpp):
// Simulation's one-ring loops with eight rings to an AVX-512 register, the same operations in the
// same order on each lane. The one-ring code's sums (area, centre of mass, momenta) are chains of
// dependent additions; here a chain serves eight rings, and the chains of up to three registers
// run side by side.

#include <cstddef>
#include <vector>

#include "lane_layout.hpp"
#include "simd_dispatch.hpp"

namespace softdrop::lanes {

#if defined(SOFTDROP_AVX_DISPATCH)
namespace {

// -x to the bit (the sign flipped, as C++'s unary minus does), with AVX-512F alone.
SOFTDROP_AVX512 inline __m512d negate(__m512d x) {
  return _mm512_castsi512_pd(
      _mm512_xor_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(static_cast<long long>(0x8000000000000000ULL))));
}

// Register g of mass i.
template <int L>
inline std::ptrdiff_t at(int i, int g) {
  return static_cast<std::ptrdiff_t>(i) * L + 8 * g;
}

template <int K>
SOFTDROP_AVX512 void forces_k(const StepConstants& k, const double* X, const double* Y, const double* PX,
                              const double* PY, double* FX, double* FY, double* area, int n) {
  constexpr int L = 8 * K;
  const __m512d zero = _mm512_setzero_pd();
  // ring_area: twice += x[j] y[i] - x[i] y[j] with j the mass before i, from mass 0; area = twice / 2.
  __m512d twice[K];
  for (int g = 0; g < K; ++g) twice[g] = zero;
  for (int i = 0, j = n - 1; i < n; j = i++)
    for (int g = 0; g < K; ++g) {
      const __m512d xi = _mm512_loadu_pd(X + at<L>(i, g)), yi = _mm512_loadu_pd(Y + at<L>(i, g));
      const __m512d xj = _mm512_loadu_pd(X + at<L>(j, g)), yj = _mm512_loadu_pd(Y + at<L>(j, g));
      twice[g] = _mm512_add_pd(twice[g], _mm512_sub_pd(_mm512_mul_pd(xj, yi), _mm512_mul_pd(xi, yj)));
    }
  const __m512d ks = _mm512_set1_pd(k.ks), kd = _mm512_set1_pd(k.kd), inv_dt = _mm512_set1_pd(k.inv_dt);
  const __m512d d0 = _mm512_set1_pd(k.rest_length), weight = _mm512_set1_pd(k.weight);
  const __m512d minus_zero = _mm512_set1_pd(-0.0);
  for (int g = 0; g < K; ++g) {
    const __m512d a = _mm512_mul_pd(_mm512_set1_pd(0.5), twice[g]);
    _mm512_storeu_pd(area + 8 * g, a);
    const __m512d half_p = _mm512_div_pd(_mm512_set1_pd(k.half_nrt), a), minus_half_p = negate(half_p);
    // Spring and edge i join masses i and i + 1 (the last: n - 1 and 0). Mass m >= 1 gets, after
    // its weight, (f - spring m-1's minus) + spring m's plus, then + edge m-1, + edge m; mass 0
    // (f + spring 0's plus) - spring n-1's minus, then + edge 0, + edge n-1 (accumulate_springs,
    // accumulate_pressure).
    __m512d first_plus_x = zero, first_plus_y = zero, first_ex = zero, first_ey = zero;
    __m512d last_minus_x = zero, last_minus_y = zero, last_ex = zero, last_ey = zero;
    for (int i = 0; i < n; ++i) {
      const int j = i + 1 == n ? 0 : i + 1;
      const __m512d xi = _mm512_loadu_pd(X + at<L>(i, g)), xj = _mm512_loadu_pd(X + at<L>(j, g));
      const __m512d yi = _mm512_loadu_pd(Y + at<L>(i, g)), yj = _mm512_loadu_pd(Y + at<L>(j, g));
      const __m512d pxi = _mm512_loadu_pd(PX + at<L>(i, g)), pxj = _mm512_loadu_pd(PX + at<L>(j, g));
      const __m512d pyi = _mm512_loadu_pd(PY + at<L>(i, g)), pyj = _mm512_loadu_pd(PY + at<L>(j, g));
      const __m512d dx = _mm512_sub_pd(xj, xi), dy = _mm512_sub_pd(yj, yi);
      const __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
      const __m512d d = _mm512_mask_sqrt_pd(d2, 0xFF, d2);  // all lanes (GCC 12's _mm512_sqrt_pd warns)
      const __m512d ux = _mm512_div_pd(dx, d), uy = _mm512_div_pd(dy, d);
      const __m512d dvx = _mm512_mul_pd(_mm512_sub_pd(_mm512_sub_pd(xj, pxj), _mm512_sub_pd(xi, pxi)), inv_dt);
      const __m512d dvy = _mm512_mul_pd(_mm512_sub_pd(_mm512_sub_pd(yj, pyj), _mm512_sub_pd(yi, pyi)), inv_dt);
      const __m512d f = _mm512_add_pd(_mm512_mul_pd(ks, _mm512_sub_pd(d, d0)),
                                      _mm512_mul_pd(kd, _mm512_add_pd(_mm512_mul_pd(dvx, ux), _mm512_mul_pd(dvy, uy))));
      const __m512d sx = _mm512_mul_pd(f, ux), sy = _mm512_mul_pd(f, uy);
      // A spring of no length adds -0 to its first end and subtracts +0 from its second (NaN: has
      // a length, as in the one-ring code).
      const __mmask8 has_length = _mm512_cmp_pd_mask(d, zero, _CMP_NEQ_UQ);
      const __m512d plus_x = _mm512_mask_blend_pd(has_length, minus_zero, sx);
      const __m512d plus_y = _mm512_mask_blend_pd(has_length, minus_zero, sy);
      const __m512d minus_x = _mm512_maskz_mov_pd(has_length, sx), minus_y = _mm512_maskz_mov_pd(has_length, sy);
      // P l_e along the outward normal, half to each end: half_p (y[i+1] - y[i]), -half_p (x[i+1] - x[i]).
      const __m512d ex = _mm512_mul_pd(half_p, dy), ey = _mm512_mul_pd(minus_half_p, dx);
      if (i == 0) {
        first_plus_x = plus_x;
        first_plus_y = plus_y;
        first_ex = ex;
        first_ey = ey;
      } else {
        const __m512d fx = _mm512_add_pd(_mm512_sub_pd(zero, last_minus_x), plus_x);
        const __m512d fy = _mm512_add_pd(_mm512_sub_pd(weight, last_minus_y), plus_y);
        _mm512_storeu_pd(FX + at<L>(i, g), _mm512_add_pd(_mm512_add_pd(fx, last_ex), ex));
        _mm512_storeu_pd(FY + at<L>(i, g), _mm512_add_pd(_mm512_add_pd(fy, last_ey), ey));
      }
      last_minus_x = minus_x;
      last_minus_y = minus_y;
      last_ex = ex;
      last_ey = ey;
    }
    const __m512d fx = _mm512_sub_pd(_mm512_add_pd(zero, first_plus_x), last_minus_x);
    const __m512d fy = _mm512_sub_pd(_mm512_add_pd(weight, first_plus_y), last_minus_y);
    _mm512_storeu_pd(FX + at<L>(0, g), _mm512_add_pd(_mm512_add_pd(fx, first_ex), last_ex));
    _mm512_storeu_pd(FY + at<L>(0, g), _mm512_add_pd(_mm512_add_pd(fy, first_ey), last_ey));
  }
}

template <int K>
SOFTDROP_AVX512 void viscosity_k(const StepConstants& k, const double* X, const double* Y, const double* PX,
                                 const double* PY, double* FX, double* FY, int n) {
  constexpr int L = 8 * K;
  const __m512d zero = _mm512_setzero_pd(), inv_dt = _mm512_set1_pd(k.inv_dt);
  __m512d cx[K], cy[K], vx[K], vy[K];
  for (int g = 0; g < K; ++g) cx[g] = cy[g] = vx[g] = vy[g] = zero;
  for (int i = 0; i < n; ++i)
    for (int g = 0; g < K; ++g) {
      const __m512d x = _mm512_loadu_pd(X + at<L>(i, g)), y = _mm512_loadu_pd(Y + at<L>(i, g));
      cx[g] = _mm512_add_pd(cx[g], x);
      cy[g] = _mm512_add_pd(cy[g], y);
      vx[g] = _mm512_add_pd(vx[g], _mm512_sub_pd(x, _mm512_loadu_pd(PX + at<L>(i, g))));
      vy[g] = _mm512_add_pd(vy[g], _mm512_sub_pd(y, _mm512_loadu_pd(PY + at<L>(i, g))));
    }
  const __m512d count = _mm512_set1_pd(n), scale = _mm512_set1_pd(k.inv_dt / n);
  __m512d ang[K], inertia[K];
  for (int g = 0; g < K; ++g) {
    cx[g] = _mm512_div_pd(cx[g], count);
    cy[g] = _mm512_div_pd(cy[g], count);
    vx[g] = _mm512_mul_pd(vx[g], scale);
    vy[g] = _mm512_mul_pd(vy[g], scale);
    ang[g] = inertia[g] = zero;
  }
  for (int i = 0; i < n; ++i)
    for (int g = 0; g < K; ++g) {
      const __m512d x = _mm512_loadu_pd(X + at<L>(i, g)), y = _mm512_loadu_pd(Y + at<L>(i, g));
      const __m512d rx = _mm512_sub_pd(x, cx[g]), ry = _mm512_sub_pd(y, cy[g]);
      const __m512d ux = _mm512_sub_pd(_mm512_mul_pd(_mm512_sub_pd(x, _mm512_loadu_pd(PX + at<L>(i, g))), inv_dt), vx[g]);
      const __m512d uy = _mm512_sub_pd(_mm512_mul_pd(_mm512_sub_pd(y, _mm512_loadu_pd(PY + at<L>(i, g))), inv_dt), vy[g]);
      ang[g] = _mm512_add_pd(ang[g], _mm512_sub_pd(_mm512_mul_pd(rx, uy), _mm512_mul_pd(ry, ux)));
      inertia[g] = _mm512_add_pd(inertia[g], _mm512_add_pd(_mm512_mul_pd(rx, rx), _mm512_mul_pd(ry, ry)));
    }
  const __m512d c = _mm512_set1_pd(k.viscous);
  for (int g = 0; g < K; ++g) {
    // omega = inertia > 0 ? ang / inertia : 0
    const __m512d omega = _mm512_maskz_div_pd(_mm512_cmp_pd_mask(inertia[g], zero, _CMP_GT_OQ), ang[g], inertia[g]);
    for (int i = 0; i < n; ++i) {
      const std::ptrdiff_t e = at<L>(i, g);
      const __m512d x = _mm512_loadu_pd(X + e), y = _mm512_loadu_pd(Y + e);
      const __m512d rx = _mm512_sub_pd(x, cx[g]), ry = _mm512_sub_pd(y, cy[g]);
      const __m512d wx = _mm512_sub_pd(vx[g], _mm512_mul_pd(omega, ry));
      const __m512d wy = _mm512_add_pd(vy[g], _mm512_mul_pd(omega, rx));
      const __m512d ux = _mm512_sub_pd(_mm512_mul_pd(_mm512_sub_pd(x, _mm512_loadu_pd(PX + e)), inv_dt), wx);
      const __m512d uy = _mm512_sub_pd(_mm512_mul_pd(_mm512_sub_pd(y, _mm512_loadu_pd(PY + e)), inv_dt), wy);
      _mm512_storeu_pd(FX + e, _mm512_sub_pd(_mm512_loadu_pd(FX + e), _mm512_mul_pd(c, ux)));
      _mm512_storeu_pd(FY + e, _mm512_sub_pd(_mm512_loadu_pd(FY + e), _mm512_mul_pd(c, uy)));
    }
  }
}

SOFTDROP_AVX512 void verlet_lanes(double h2m, double* X, double* Y, double* PX, double* PY, const double* FX,
                                  const double* FY, std::ptrdiff_t size) {
  const __m512d two = _mm512_set1_pd(2.0), h = _mm512_set1_pd(h2m);
  for (std::ptrdiff_t e = 0; e < size; e += 8) {
    const __m512d x = _mm512_loadu_pd(X + e), y = _mm512_loadu_pd(Y + e);
    const __m512d nx = _mm512_add_pd(_mm512_sub_pd(_mm512_mul_pd(two, x), _mm512_loadu_pd(PX + e)),
                                     _mm512_mul_pd(_mm512_loadu_pd(FX + e), h));
    const __m512d ny = _mm512_add_pd(_mm512_sub_pd(_mm512_mul_pd(two, y), _mm512_loadu_pd(PY + e)),
                                     _mm512_mul_pd(_mm512_loadu_pd(FY + e), h));
    _mm512_storeu_pd(PX + e, x);
    _mm512_storeu_pd(PY + e, y);
    _mm512_storeu_pd(X + e, nx);
    _mm512_storeu_pd(Y + e, ny);
  }
}

}  // namespace

StepConstants step_constants(const DropletParams& p) {
  StepConstants k;
  k.weight = p.mass * p.gravity;  // accumulate_gravity
  k.ks = p.ks;
  k.kd = p.kd;
  k.inv_dt = 1.0 / p.dt;
  k.rest_length = p.rest_length();  // Simulation's rest_length()
  k.half_nrt = 0.5 * p.nrt;         // accumulate_pressure: 0.5 nRT / area
  k.viscous = p.mass * p.viscosity;
  k.h2m = p.dt * p.dt / p.mass;     // integrate
  return k;
}

void forces_before_contacts(const StepConstants& k, const double* X, const double* Y, const double* PX,
                            const double* PY, double* FX, double* FY, double* area, int n, int registers) {
  with_registers(registers, [&](auto r) { forces_k<decltype(r)::value>(k, X, Y, PX, PY, FX, FY, area, n); });
}

void viscosity(const StepConstants& k, const double* X, const double* Y, const double* PX, const double* PY,
               double* FX, double* FY, int n, int registers) {
  with_registers(registers, [&](auto r) { viscosity_k<decltype(r)::value>(k, X, Y, PX, PY, FX, FY, n); });
}

void integrate(double h2m, double* X, double* Y, double* PX, double* PY, const double* FX, const double* FY, int n,
               int registers) {
  verlet_lanes(h2m, X, Y, PX, PY, FX, FY, static_cast<std::ptrdiff_t>(n) * 8 * registers);
}

double* step_scratch(std::size_t doubles) {
  thread_local std::vector<double> scratch;
  if (scratch.size() < doubles) scratch.resize(doubles);
  return scratch.data();
}
#endif

}  // namespace softdrop::lanes
