#include "softdrop/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <condition_variable>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "contact_lanes.hpp"
#include "lane_layout.hpp"
#include "simd_dispatch.hpp"
#include "validation.hpp"

namespace softdrop {

const char* to_string(Outcome outcome) {
  switch (outcome) {
    case Outcome::passed: return "passed";
    case Outcome::stuck: return "stuck";
    case Outcome::timeout: return "timeout";
    case Outcome::diverged: return "diverged";
  }
  return "?";
}

bool RunOptions::IsValid(std::string* why) const {
  using detail::fail;
  using detail::num;
  if (max_steps <= 0) return fail(why, "max-steps = " + std::to_string(max_steps) + ": must be > 0");
  if (!std::isfinite(stuck_window) || stuck_window <= 0)
    return fail(why, "stuck-window = " + num(stuck_window) + ": must be > 0");
  if (!std::isfinite(stuck_distance) || stuck_distance < 0)
    return fail(why, "stuck-distance = " + num(stuck_distance) + ": must be >= 0");
  if (!std::isfinite(rest_window) || rest_window < 0)
    return fail(why, "rest-window = " + num(rest_window) + ": must be >= 0 (0: no rest test)");
  if (!std::isfinite(rest_distance) || rest_distance < 0)
    return fail(why, "rest-distance = " + num(rest_distance) + ": must be >= 0");
  if (check_interval <= 0)
    return fail(why, "check-interval = " + std::to_string(check_interval) + ": must be > 0");
  if (path_interval < 0)
    return fail(why, "path-interval = " + std::to_string(path_interval) + ": must be >= 0");
  if (area_interval < 0)
    return fail(why, "trace-interval = " + std::to_string(area_interval) + ": must be >= 0");
  for (double t : snapshot_times)
    if (!std::isfinite(t) || t < 0)
      return fail(why, "snapshot-times: " + num(t) + " must be finite and >= 0");
  return true;
}

namespace {
// The contact grid's halo, in cells: a mass's anchor ball (apply_contact_limit) may reach past its
// cell's edge by this much, so a mass moving through open pore space leaves its ball, and is
// tested against its whole cell, less often (sweep-long: 2.4 M of 127 M mass tests went to the
// cell with no halo, 0.53 M with half a cell; a cell then lists 2.2 times as many discs).
constexpr double kContactGridHalo = 0.5;
}  // namespace

Simulation::Simulation(const DropletParams& params, const Medium& medium)
    : params_(params), medium_(medium), grid_(medium, 0, kContactGridHalo) {
  std::string why;
  if (!params.IsValid(&why)) throw std::invalid_argument(why);
  if (!medium.IsValid(&why)) throw std::invalid_argument(why);
  rest_length_ = params.rest_length();
  area0_ = params.inflated_area();
  // Only masses are tested against grains; a grain narrower than an edge could slip between two.
  const double longest_edge = (1 + params.max_strain) * rest_length_;
  for (std::size_t i = 0; i < medium.grains.size(); ++i)
    if (medium.grains[i].r < longest_edge)
      throw std::invalid_argument("grain " + std::to_string(i) + " radius " +
                                  detail::num(medium.grains[i].r) +
                                  " is smaller than the droplet's longest edge " +
                                  detail::num(longest_edge) +
                                  ": use more masses, a smaller radius or larger grains");
  touched_.assign(medium.grains.size() + 1, 0);  // the last entry: no grain (contact_touch_'s)
  double top = medium.height;
  for (const Grain& g : medium.grains) top = std::max(top, g.y + g.r);
  start_y_ = top + params.radius + 0.05 * params.radius;
  // Far above the rounding of any distance in the box (about 1e-15 of its size), far below any
  // distance that matters.
  clearance_margin_ = 1e-9 * (medium.width + start_y_);
  place(0.5 * medium.width, start_y_);
}

void Simulation::place(double cx, double cy) {
  state_changed();
  place_droplet(params_, cx, cy, &state_);
  // Start at rest at t = 0: x(-dt) = x(0) + g dt^2 / 2 makes Verlet exact for free fall.
  for (int i = 0; i < state_.size(); ++i) state_.py[i] += 0.5 * params_.gravity * params_.dt * params_.dt;
  std::fill(touched_.begin(), touched_.end(), 0);
  spring_force_.assign(4 * state_.x.size(), 0.0);  // so that step() allocates nothing
  // A point is rarely inside more than a few discs; a mass inside more than this is looked up
  // again by the collisions. (A cell's full count could be thousands in a coarse grid.)
  contact_capacity_ = std::min<std::size_t>(grid_.max_cell_entries(), 8);
  contacts_.assign(state_.x.size() * contact_capacity_, GrainGrid::Disc{});
  contact_count_.assign(state_.x.size(), 0);
  contact_x_.assign(state_.x.size(), std::numeric_limits<double>::quiet_NaN());  // matches no position
  contact_y_.assign(state_.y.size(), std::numeric_limits<double>::quiet_NaN());
  clear_x_.assign(state_.x.size(), 0.0);
  clear_y_.assign(state_.x.size(), 0.0);
  clear_r2_.assign(state_.x.size(), -1.0);
  clear_count_.assign(state_.x.size(), 0);
  clear_discs_.assign(contacts_.size(), GrainGrid::Disc{});
  for (std::vector<double>* v : {&contact_disc_x_, &contact_disc_y_, &contact_disc_r_})
    v->assign(state_.x.size(), 0.0);
  contact_disc_grain_.assign(state_.x.size(), 0);
  contact_fx_.assign(state_.x.size(), -0.0);
  contact_fy_.assign(state_.x.size(), -0.0);
  contact_touch_.assign(state_.x.size(), static_cast<std::int32_t>(medium_.grains.size()));
  contact_todo_.clear();
  contact_todo_.reserve(state_.x.size());
  contact_deepest_ = 0;
  area_ = ring_area(state_);
  last_penetration_ = 0;
}

void Simulation::place_above(double cx) { place(cx, start_y_); }

void Simulation::centre_of_mass(double* cx, double* cy) const {
  const int n = state_.size();
  double sx = 0, sy = 0;
  for (int i = 0; i < n; ++i) {
    sx += state_.x[i];
    sy += state_.y[i];
  }
  *cx = sx / n;
  *cy = sy / n;
}

// ---- Stages of a step -------------------------------------------------------------------------

namespace {
// Equal to the bit (unlike ==, which does not tell -0 from +0, and NaN from itself).
inline bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// x - W floor(x / W), the position of x in [0, W). Inside the box (0 < x < 0.999999 W) that
// expression is x exactly (the quotient rounds below 1, so the floor is 0), so the division is
// skipped there: same bits, a division fewer per mass in the common case.
inline double wrap_periodic(double x, double W) {
  return x > 0 && x < 0.999999 * W ? x : x - W * std::floor(x / W);
}

// A mass at x needs no wall force: the medium is periodic, or x is within [0, W] (NaN included, as
// the walls' tests `x < 0` and `x > W` are false for it).
inline bool within_walls(double x, bool periodic, double W) { return periodic || !(x < 0 || x > W); }
}  // namespace

void Simulation::accumulate_gravity() {
  const double w = params_.mass * params_.gravity;
  std::fill(state_.fx.begin(), state_.fx.end(), 0.0);
  std::fill(state_.fy.begin(), state_.fy.end(), w);
}

namespace {
// Force of spring (i, j) on i along the spring (> 0 pulls i towards j), and its components.
struct SpringInput {
  double ks, kd, inv_dt, d0;
};
inline void spring_force(const SpringInput& k, double xi, double yi, double xj, double yj, double pxi,
                         double pyi, double pxj, double pyj, double* sx, double* sy, bool* zero) {
  const double dx = xj - xi, dy = yj - yi;
  const double d = std::sqrt(dx * dx + dy * dy);
  *zero = d == 0;
  if (*zero) return;
  const double ux = dx / d, uy = dy / d;
  // Relative velocity of j with respect to i, projected on the spring.
  const double dvx = ((xj - pxj) - (xi - pxi)) * k.inv_dt;
  const double dvy = ((yj - pyj) - (yi - pyi)) * k.inv_dt;
  const double f = k.ks * (d - k.d0) + k.kd * (dvx * ux + dvy * uy);
  *sx = f * ux;
  *sy = f * uy;
}

#if defined(SOFTDROP_AVX_DISPATCH)
// Springs (i, i+1) four at a time while i + 4 < n: the SSE2 loop of accumulate_springs() with
// four lanes, the same operations on each. Returns the first spring not done.
SOFTDROP_AVX int spring_forces_avx(const SpringInput& in, const double* x, const double* y, const double* px,
                                   const double* py, int n, double* plus_x, double* plus_y, double* minus_x,
                                   double* minus_y) {
  const __m256d ks = _mm256_set1_pd(in.ks), kd = _mm256_set1_pd(in.kd), inv_dt = _mm256_set1_pd(in.inv_dt);
  const __m256d d0 = _mm256_set1_pd(in.d0), zero = _mm256_setzero_pd(), minus_zero = _mm256_set1_pd(-0.0);
  int i = 0;
  for (; i + 4 < n; i += 4) {
    const __m256d xi = _mm256_loadu_pd(x + i), xj = _mm256_loadu_pd(x + i + 1);
    const __m256d yi = _mm256_loadu_pd(y + i), yj = _mm256_loadu_pd(y + i + 1);
    const __m256d pxi = _mm256_loadu_pd(px + i), pxj = _mm256_loadu_pd(px + i + 1);
    const __m256d pyi = _mm256_loadu_pd(py + i), pyj = _mm256_loadu_pd(py + i + 1);
    const __m256d dx = _mm256_sub_pd(xj, xi), dy = _mm256_sub_pd(yj, yi);
    const __m256d d = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
    const __m256d ux = _mm256_div_pd(dx, d), uy = _mm256_div_pd(dy, d);
    const __m256d dvx = _mm256_mul_pd(_mm256_sub_pd(_mm256_sub_pd(xj, pxj), _mm256_sub_pd(xi, pxi)), inv_dt);
    const __m256d dvy = _mm256_mul_pd(_mm256_sub_pd(_mm256_sub_pd(yj, pyj), _mm256_sub_pd(yi, pyi)), inv_dt);
    const __m256d f = _mm256_add_pd(_mm256_mul_pd(ks, _mm256_sub_pd(d, d0)),
                                    _mm256_mul_pd(kd, _mm256_add_pd(_mm256_mul_pd(dvx, ux), _mm256_mul_pd(dvy, uy))));
    const __m256d sx = _mm256_mul_pd(f, ux), sy = _mm256_mul_pd(f, uy);
    const __m256d has_length = _mm256_cmp_pd(d, zero, _CMP_NEQ_UQ);  // as _mm_cmpneq_pd (NaN: true)
    const __m256d no_length = _mm256_andnot_pd(has_length, minus_zero);
    _mm256_storeu_pd(plus_x + i, _mm256_or_pd(_mm256_and_pd(has_length, sx), no_length));
    _mm256_storeu_pd(plus_y + i, _mm256_or_pd(_mm256_and_pd(has_length, sy), no_length));
    _mm256_storeu_pd(minus_x + i, _mm256_and_pd(has_length, sx));
    _mm256_storeu_pd(minus_y + i, _mm256_and_pd(has_length, sy));
  }
  return i;
}
#endif
}  // namespace

void Simulation::accumulate_springs() {
  // Two passes: the force of every spring (independent, four at a time with AVX, two with SSE2,
  // as constraint_vector_width() allows), then each mass
  // gathers its two springs in the order of the scalar loop "for each spring i: f[i] += s,
  // f[i+1] -= s" (mass m >= 1: (f - s[m-1]) + s[m]; mass 0: (f + s[0]) - s[n-1]), so the sums
  // have the same bits.
  const int n = state_.size();
  const SpringInput in{params_.ks, params_.kd, 1.0 / params_.dt, rest_length_};
  const std::size_t un = static_cast<std::size_t>(n);
  if (spring_force_.size() != 4 * un) spring_force_.assign(4 * un, 0.0);
  double* plus_x = spring_force_.data();  // added to the first end; -0 if the spring has no length
  double* plus_y = plus_x + un;
  double* minus_x = plus_y + un;          // subtracted from the second end; +0 then
  double* minus_y = minus_x + un;
  double* fx = state_.fx.data();
  double* fy = state_.fy.data();
  const double *x = state_.x.data(), *y = state_.y.data();
  const double *px = state_.px.data(), *py = state_.py.data();
  int i = 0;
#if defined(SOFTDROP_AVX_DISPATCH)
  if (constraint_vector_width() >= VectorWidth::avx)
    i = spring_forces_avx(in, x, y, px, py, n, plus_x, plus_y, minus_x, minus_y);
#endif
#if defined(__SSE2__)
  if (constraint_vector_width() != VectorWidth::scalar) {
    const __m128d ks = _mm_set1_pd(in.ks), kd = _mm_set1_pd(in.kd), inv_dt = _mm_set1_pd(in.inv_dt);
    const __m128d d0 = _mm_set1_pd(in.d0), zero = _mm_setzero_pd(), minus_zero = _mm_set1_pd(-0.0);
    for (; i + 2 < n; i += 2) {  // springs (i, i+1) and (i+1, i+2), both inside the arrays
      const __m128d xi = _mm_loadu_pd(x + i), xj = _mm_loadu_pd(x + i + 1);
      const __m128d yi = _mm_loadu_pd(y + i), yj = _mm_loadu_pd(y + i + 1);
      const __m128d pxi = _mm_loadu_pd(px + i), pxj = _mm_loadu_pd(px + i + 1);
      const __m128d pyi = _mm_loadu_pd(py + i), pyj = _mm_loadu_pd(py + i + 1);
      const __m128d dx = _mm_sub_pd(xj, xi), dy = _mm_sub_pd(yj, yi);
      const __m128d d = _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)));
      const __m128d ux = _mm_div_pd(dx, d), uy = _mm_div_pd(dy, d);
      const __m128d dvx = _mm_mul_pd(_mm_sub_pd(_mm_sub_pd(xj, pxj), _mm_sub_pd(xi, pxi)), inv_dt);
      const __m128d dvy = _mm_mul_pd(_mm_sub_pd(_mm_sub_pd(yj, pyj), _mm_sub_pd(yi, pyi)), inv_dt);
      const __m128d f = _mm_add_pd(_mm_mul_pd(ks, _mm_sub_pd(d, d0)),
                                   _mm_mul_pd(kd, _mm_add_pd(_mm_mul_pd(dvx, ux), _mm_mul_pd(dvy, uy))));
      const __m128d sx = _mm_mul_pd(f, ux), sy = _mm_mul_pd(f, uy);
      const __m128d has_length = _mm_cmpneq_pd(d, zero);
      _mm_storeu_pd(plus_x + i, _mm_or_pd(_mm_and_pd(has_length, sx), _mm_andnot_pd(has_length, minus_zero)));
      _mm_storeu_pd(plus_y + i, _mm_or_pd(_mm_and_pd(has_length, sy), _mm_andnot_pd(has_length, minus_zero)));
      _mm_storeu_pd(minus_x + i, _mm_and_pd(has_length, sx));
      _mm_storeu_pd(minus_y + i, _mm_and_pd(has_length, sy));
    }
  }
#endif
  for (; i < n; ++i) {
    const int j = i + 1 == n ? 0 : i + 1;
    double sx = 0, sy = 0;
    bool zero = false;
    spring_force(in, x[i], y[i], x[j], y[j], px[i], py[i], px[j], py[j], &sx, &sy, &zero);
    // Adding -0 and subtracting +0 leave every double (-0 included) as it is.
    plus_x[i] = zero ? -0.0 : sx;
    plus_y[i] = zero ? -0.0 : sy;
    minus_x[i] = zero ? 0.0 : sx;
    minus_y[i] = zero ? 0.0 : sy;
  }
  fx[0] = (fx[0] + plus_x[0]) - minus_x[n - 1];
  fy[0] = (fy[0] + plus_y[0]) - minus_y[n - 1];
  for (int m = 1; m < n; ++m) {
    fx[m] = (fx[m] - minus_x[m - 1]) + plus_x[m];
    fy[m] = (fy[m] - minus_y[m - 1]) + plus_y[m];
  }
}

void Simulation::accumulate_pressure() {
  area_ = ring_area(state_);
  const int n = state_.size();
  // P l_e along the outward normal (dy, -dx) / l_e of a counter-clockwise edge, half to each end.
  // Each mass gathers its two edges in the order of the loop "for each edge i: f[i] += e,
  // f[i+1] += e": mass m >= 1 adds e[m-1] then e[m]; mass 0 adds e[0] then e[n-1].
  const double half_p = 0.5 * params_.nrt / area_, minus_half_p = -half_p;
  double* fx = state_.fx.data();
  double* fy = state_.fy.data();
  const double *x = state_.x.data(), *y = state_.y.data();
  const double ex_last = half_p * (y[0] - y[n - 1]), ey_last = minus_half_p * (x[0] - x[n - 1]);
  const double ex_first = half_p * (y[1] - y[0]), ey_first = minus_half_p * (x[1] - x[0]);
  for (int m = 1; m + 1 < n; ++m) {
    fx[m] = (fx[m] + half_p * (y[m] - y[m - 1])) + half_p * (y[m + 1] - y[m]);
    fy[m] = (fy[m] + minus_half_p * (x[m] - x[m - 1])) + minus_half_p * (x[m + 1] - x[m]);
  }
  fx[n - 1] = (fx[n - 1] + half_p * (y[n - 1] - y[n - 2])) + ex_last;
  fy[n - 1] = (fy[n - 1] + minus_half_p * (x[n - 1] - x[n - 2])) + ey_last;
  fx[0] = (fx[0] + ex_first) + ex_last;
  fy[0] = (fy[0] + ey_first) + ey_last;
}

void Simulation::accumulate_collisions() { accumulate_collisions(state_.fx.data(), state_.fy.data(), 1); }

void Simulation::accumulate_collisions(double* fx, double* fy, std::ptrdiff_t stride, bool recorded_added) {
  const int n = state_.size();
  const double kc = params_.kc, cc = params_.cc, inv_dt = 1.0 / params_.dt;
  const double W = medium_.width;
  const bool periodic = medium_.periodic;
  double deepest = 0;
  // The arrays as locals: the touched set's byte stores may alias anything, and would otherwise make
  // the compiler reload every vector's data pointer after each of them.
  const double *xs = state_.x.data(), *ys = state_.y.data(), *pxs = state_.px.data(), *pys = state_.py.data();
  const double *cxs = contact_x_.data(), *cys = contact_y_.data();
  const std::int32_t* counts = contact_count_.data();
  const GrainGrid::Disc* const contacts = contacts_.data();
  const double *first_x = contact_disc_x_.data(), *first_y = contact_disc_y_.data(),
               *first_r = contact_disc_r_.data();
  const std::int32_t* first_grain = contact_disc_grain_.data();
  const std::size_t capacity = contact_capacity_;
  std::uint8_t* const touched = touched_.data();
  // Mass i's contacts, for any mass but one recorded free within the walls.
  const auto collide_mass = [&](int i) {
    const double x = xs[i], y = ys[i];
    const bool recorded = same_bits(x, cxs[i]) && same_bits(y, cys[i]);
    const double vx = (x - pxs[i]) * inv_dt, vy = (y - pys[i]) * inv_dt;
    const double xw = periodic ? wrap_periodic(x, W) : x;
    // Penalty spring from the surface point plus damping of the normal velocity; never pulls.
    const auto collide = [&](double gx, double gy, double r, std::int32_t grain) {
      const double dx = xw - gx, dy = y - gy;
      const double d2 = dx * dx + dy * dy;
      if (d2 >= r * r) return;
      const double d = std::sqrt(d2);
      const double nx = d > 0 ? dx / d : 0.0, ny = d > 0 ? dy / d : 1.0, depth = r - d;
      const double f = std::max(0.0, kc * depth - cc * (vx * nx + vy * ny));
      fx[i * stride] += f * nx;
      fy[i * stride] += f * ny;
      touched[static_cast<std::size_t>(grain)] = 1;
      deepest = std::max(deepest, depth);
    };
    // The same discs in the same order as the grid's, less those the mass is not inside (the
    // record; one disc is kept apart, the lanes' records of one included).
    if (recorded && (counts[i] == 1 || counts[i] == lanes::kOneDiscWithForce)) {
      collide(first_x[i], first_y[i], first_r[i], first_grain[i]);
    } else {
      const GrainGrid::Disc* const record = contacts + static_cast<std::size_t>(i) * capacity;
      const auto range = recorded ? GrainGrid::DiscRange{record, record + counts[i]} : grid_.discs_near(xw, y);
      for (const GrainGrid::Disc* g = range.begin; g != range.end; ++g) collide(g->x, g->y, g->r, g->grain);
    }
    if (!periodic) {  // solid side walls
      if (x < 0) fx[i * stride] += std::max(0.0, -kc * x - cc * vx);
      if (x > W) fx[i * stride] -= std::max(0.0, kc * (x - W) + cc * vx);
    }
  };
  if (records_current_) {
    // The contact limit left the forces of the masses inside one disc (-0 for the others, which
    // changes no double), their grains and their largest depth, at these very positions and
    // velocities: every mass gets its force with no test, and those it did not cover are listed.
    records_current_ = false;
    const double *force_x = contact_fx_.data(), *force_y = contact_fy_.data();
    if (!recorded_added) {
      for (int i = 0; i < n; ++i) {
        fx[i * stride] += force_x[i];
        fy[i * stride] += force_y[i];
      }
    }
    const std::int32_t* touch = contact_touch_.data();
    for (int i = 0; i < n; ++i) touched[static_cast<std::size_t>(touch[i])] = 1;
    deepest = contact_deepest_;  // the maximum does not depend on the order of the masses
    for (const std::int32_t i : contact_todo_) collide_mass(i);
  } else {
    for (int i = 0; i < n; ++i) {
      // Most masses touch nothing: recorded inside no disc, and within the walls.
      const double x = xs[i], y = ys[i];
      if (same_bits(x, cxs[i]) && same_bits(y, cys[i]) && counts[i] == 0 && within_walls(x, periodic, W))
        continue;
      collide_mass(i);
    }
  }
  last_penetration_ = deepest;
}

void Simulation::accumulate_viscosity() {
  // Rigid motion of the ring from its linear and angular momentum; the viscous force acts on the
  // rest, so it sums to zero force and zero torque.
  const int n = state_.size();
  const double inv_dt = 1.0 / params_.dt;
  const double *x = state_.x.data(), *y = state_.y.data(), *px = state_.px.data(), *py = state_.py.data();
  double cx = 0, cy = 0, vx = 0, vy = 0;
  for (int i = 0; i < n; ++i) {
    cx += x[i];
    cy += y[i];
    vx += x[i] - px[i];
    vy += y[i] - py[i];
  }
  cx /= n;
  cy /= n;
  vx *= inv_dt / n;
  vy *= inv_dt / n;
  double ang = 0, inertia = 0;
  for (int i = 0; i < n; ++i) {
    const double rx = x[i] - cx, ry = y[i] - cy;
    ang += rx * ((y[i] - py[i]) * inv_dt - vy) - ry * ((x[i] - px[i]) * inv_dt - vx);
    inertia += rx * rx + ry * ry;
  }
  const double omega = inertia > 0 ? ang / inertia : 0.0;
  const double c = params_.mass * params_.viscosity;
  for (int i = 0; i < n; ++i) {
    const double rx = x[i] - cx, ry = y[i] - cy;
    state_.fx[i] -= c * ((x[i] - px[i]) * inv_dt - (vx - omega * ry));
    state_.fy[i] -= c * ((y[i] - py[i]) * inv_dt - (vy + omega * rx));
  }
}

void Simulation::apply_contact_limit() {
  // Inverse dynamics for contacts: no mass stays deeper than max_depth inside a grain, and one
  // that is pushed back loses the normal velocity that carried it in (an inelastic stop).
  const int n = state_.size();
  const double W = medium_.width, limit = params_.max_depth;
  const bool periodic = medium_.periodic;
  const std::size_t capacity = contact_capacity_;
  const auto first_contact = [this](int i, const GrainGrid::Disc& g) {
    contact_disc_x_[i] = g.x;
    contact_disc_y_[i] = g.y;
    contact_disc_r_[i] = g.r;
    contact_disc_grain_[i] = g.grain;
  };
  const std::int32_t no_grain = static_cast<std::int32_t>(medium_.grains.size());
  records_current_ = false;
  contact_todo_.clear();
  alignas(64) double deepest[8] = {};  // of the forces recorded, lane by lane
  // The next collisions of a mass tested here, not eight at a time: no recorded force, and a
  // full look at its record unless it is recorded free within the walls.
  const auto leave_to_collisions = [&](int i, double x, bool free) {
    contact_fx_[i] = -0.0;
    contact_fy_[i] = -0.0;
    contact_touch_[i] = no_grain;
    if (!(free && within_walls(x, periodic, W))) contact_todo_.push_back(i);
  };
  const auto limit_mass = [&](int i) {
    const double x = state_.x[i], y = state_.y[i];
    const std::size_t first = static_cast<std::size_t>(i) * capacity;
    GrainGrid::Disc* inside = contacts_.data() + first;
    // Within its ball only the anchor's discs can hold or push the mass, and each test of the
    // others below would say so: test those discs alone, in the cell's order.
    const double ex = x - clear_x_[i], ey = y - clear_y_[i];
    if (ex * ex + ey * ey < clear_r2_[i]) {
      const int anchored = clear_count_[i];
      int count = 0;
      bool push = false;
      if (anchored > 0) {
        const double xw = periodic ? wrap_periodic(x, W) : x;
        for (const GrainGrid::Disc *g = clear_discs_.data() + first, *end = g + anchored; g != end; ++g) {
          const double dx = xw - g->x, dy = y - g->y, inner = g->r - limit;
          const double d2 = dx * dx + dy * dy;
          if (!(d2 >= g->r * g->r)) {
            if (count == 0) first_contact(i, *g);
            inside[count++] = *g;
          }
          if (inner > 0 && !(d2 >= inner * inner)) {
            push = true;  // the full test below pushes it, in the cell's order
            break;
          }
        }
      }
      if (!push) {
        contact_count_[i] = count;
        contact_x_[i] = x;
        contact_y_[i] = y;
        leave_to_collisions(i, x, count == 0);
        return;
      }
    }
    const double xw = periodic ? wrap_periodic(x, W) : x;
    const std::int64_t cell = grid_.cell_of(xw, y);
    const auto range = grid_.discs_in(cell);
    // The discs the mass is inside, tested as accumulate_collisions() will test them next step,
    // and how far it is from the surface of the nearest other one.
    int count = 0;
    double gap = std::numeric_limits<double>::infinity();
    bool pushed = false;
    for (const GrainGrid::Disc* g = range.begin; g != range.end; ++g) {
      const double dx = xw - g->x, dy = state_.y[i] - g->y, inner = g->r - limit;
      const double d2 = dx * dx + dy * dy;
      if (!(d2 >= g->r * g->r)) {
        if (count == 0) first_contact(i, *g);
        if (static_cast<std::size_t>(count) < capacity) inside[count] = *g;
        ++count;
      } else {
        gap = std::min(gap, std::sqrt(d2) - g->r);
      }
      if (inner <= 0 || d2 >= inner * inner) continue;
      const double d = std::sqrt(d2);
      const double nx = d > 0 ? dx / d : 0.0, ny = d > 0 ? dy / d : 1.0;
      const double push = inner - d;
      const double vx = state_.x[i] - state_.px[i], vy = state_.y[i] - state_.py[i];
      const double vn = std::min(0.0, vx * nx + vy * ny);  // inward displacement per step
      state_.x[i] += push * nx;
      state_.y[i] += push * ny;
      state_.px[i] = state_.x[i] - (vx - vn * nx);
      state_.py[i] = state_.y[i] - (vy - vn * ny);
      pushed = true;
      block_id_ = 0;
    }
    // A pushed mass has moved since the tests, and one inside too many discs has no full record:
    // their collisions look them up again, and they get no anchor. (A NaN position that matches
    // the marker finds no discs either way.)
    const bool recorded = !pushed && static_cast<std::size_t>(count) <= capacity;
    contact_count_[i] = recorded ? count : 0;
    contact_x_[i] = recorded ? x : std::numeric_limits<double>::quiet_NaN();
    contact_y_[i] = y;
    leave_to_collisions(i, x, recorded && count == 0);
    // No disc outside the cell's list is nearer than the cell's edge plus the grid's halo; the ball
    // must not cross the periodic seam either, where the wrapped position jumps.
    double reach = std::min(gap, grid_.edge_distance(xw, y));
    if (periodic) reach = std::min(reach, std::min(xw, W - xw));
    reach -= clearance_margin_;
    const bool anchored = recorded && reach > 0;
    clear_r2_[i] = anchored ? reach * reach : -1.0;
    clear_x_[i] = x;
    clear_y_[i] = y;
    clear_count_[i] = anchored ? count : 0;
    if (anchored) std::copy(inside, inside + count, clear_discs_.begin() + static_cast<std::ptrdiff_t>(first));
  };
  int i = 0;
#if defined(SOFTDROP_AVX_DISPATCH)
  if (constraint_vector_width() >= VectorWidth::avx) {
    // Eight masses at a time: most are in their balls, free or inside their anchor's one disc.
    lanes::ContactRecords r;
    r.x = state_.x.data();
    r.y = state_.y.data();
    r.clear_x = clear_x_.data();
    r.clear_y = clear_y_.data();
    r.clear_r2 = clear_r2_.data();
    r.clear_count = clear_count_.data();
    r.disc_x = contact_disc_x_.data();
    r.disc_y = contact_disc_y_.data();
    r.disc_r = contact_disc_r_.data();
    r.contact_x = contact_x_.data();
    r.contact_y = contact_y_.data();
    r.contact_count = contact_count_.data();
    r.disc_grain = contact_disc_grain_.data();
    r.no_grain = no_grain;
    r.px = state_.px.data();
    r.py = state_.py.data();
    r.kc = params_.kc;
    r.cc = params_.cc;
    r.inv_dt = 1.0 / params_.dt;
    r.force_x = contact_fx_.data();
    r.force_y = contact_fy_.data();
    r.touch = contact_touch_.data();
    r.periodic = periodic;
    r.width = W;
    r.wrap_below = 0.999999 * W;
    constexpr int kChunk = 16;  // groups of eight per call
    unsigned todo[kChunk];
    while (i + 8 <= n) {
      const int groups = std::min(kChunk, (n - i) / 8);
      lanes::limit_groups(r, i / 8, groups, limit, deepest, todo);
      for (int g = 0; g < groups; ++g, i += 8)
        for (unsigned left = todo[g]; left != 0; left &= left - 1) limit_mass(i + std::countr_zero(left));
    }
  }
#endif
  for (; i < n; ++i) limit_mass(i);
  // The maximum does not depend on the order.
  contact_deepest_ = *std::max_element(deepest, deepest + 8);
  records_current_ = true;
}

namespace {
// Position Verlet on six distinct arrays. __restrict parameters (GCC honours them on parameters)
// let the loop be vectorised; each element gets the same operations, so the same bits.
void verlet(double* __restrict x, double* __restrict y, double* __restrict px, double* __restrict py,
            const double* __restrict fx, const double* __restrict fy, int n, double h2m) {
  for (int i = 0; i < n; ++i) {
    const double nx = 2 * x[i] - px[i] + fx[i] * h2m;
    const double ny = 2 * y[i] - py[i] + fy[i] * h2m;
    px[i] = x[i];
    py[i] = y[i];
    x[i] = nx;
    y[i] = ny;
  }
}
}  // namespace

void Simulation::integrate() {
  state_changed();
  const double h2m = params_.dt * params_.dt / params_.mass;
  verlet(state_.x.data(), state_.y.data(), state_.px.data(), state_.py.data(), state_.fx.data(), state_.fy.data(),
         state_.size(), h2m);
}

void Simulation::compute_forces() {
  accumulate_gravity();
  accumulate_springs();
  accumulate_pressure();
  accumulate_collisions();
  if (params_.viscosity > 0) accumulate_viscosity();
}

void Simulation::apply_constraint() {
  state_changed();
  softdrop::apply_length_constraint(&state_, rest_length_, params_.max_strain,
                                    params_.constraint_iterations, params_.constraint_order);
}

bool Simulation::step() {
  before_constraint();
  apply_constraint();
  return after_constraint();
}

// ---- Checks and the run loop ------------------------------------------------------------------

bool Simulation::any_grain_inside_ring() const {
  const int n = state_.size();
  double x0 = state_.x[0], x1 = x0, y0 = state_.y[0], y1 = y0;
  for (int i = 1; i < n; ++i) {
    x0 = std::min(x0, state_.x[i]);
    x1 = std::max(x1, state_.x[i]);
    y0 = std::min(y0, state_.y[i]);
    y1 = std::max(y1, state_.y[i]);
  }
  const double W = medium_.width;
  for (const Grain& g : medium_.grains) {
    if (g.y < y0 || g.y > y1) continue;
    // The ring is unwrapped; try the grain's periodic copies that can fall in its x range.
    double gx = g.x;
    if (medium_.periodic) gx += W * std::floor((x0 - g.x) / W);
    for (; gx <= x1; gx += W) {
      if (gx >= x0 && ring_contains(state_, gx, g.y)) return true;
      if (!medium_.periodic) break;
    }
  }
  return false;
}

namespace {
double distance(double ax, double ay, double bx, double by) {
  return std::hypot(bx - ax, by - ay);
}
}  // namespace

RunSummary Simulation::run(double cx, const RunOptions& options) {
  place_above(cx);
  return run_from_current(options);
}

// One droplet's run between its steps: the path, the recordings and the exit tests. A driver
// steps the simulation and calls after_step(); run_from_current drives one droplet,
// run_interleaved several.
class RunStepper {
 public:
  RunStepper(Simulation* sim, const RunOptions& options) : sim_(sim), o_(options) {
    std::string why;
    if (!options.IsValid(&why)) throw std::invalid_argument(why);
    dt_ = sim->params_.dt;
    H_ = sim->medium_.height;
    sim->centre_of_mass(&cx_, &cy_);
    s_.start_x = cx_;
    s_.start_y = cy_;
    sim->area_ = ring_area(sim->state_);
    window_ = std::max<std::int64_t>(1, std::llround(options.stuck_window / dt_));
    rest_window_ = options.rest_window > 0 ? std::max<std::int64_t>(1, std::llround(options.rest_window / dt_)) : 0;
    for (double t : options.snapshot_times) snapshot_steps_.push_back(std::llround(t / dt_));
    std::sort(snapshot_steps_.begin(), snapshot_steps_.end());
    record(0);
    entered_ = cy_ < H_;
    checkpoint_y_ = cy_;
  }

  bool finished() const { return finished_; }
  Simulation* simulation() const { return sim_; }

  /// Book-keeping of the step just taken (ok: the step's own validity test); may end the run.
  void after_step(bool ok) {
    double cx, cy;
    sim_->centre_of_mass(&cx, &cy);
    after_step(ok, cx, cy);
  }
  /// after_step(ok), given the centre of mass the step left (cx, cy), as centre_of_mass() gives it.
  void after_step(bool ok, double cx, double cy) {
    const std::int64_t k = ++k_;
    const double pcx = cx_, pcy = cy_;
    cx_ = cx;
    cy_ = cy;
    if (!ok || !std::isfinite(cx_) || !std::isfinite(cy_)) {
      std::ostringstream r;
      r << "ring became invalid at step " << k << " (area " << sim_->area_ << ")";
      return finish(Outcome::diverged, r.str(), k);
    }
    s_.min_area_ratio = std::min(s_.min_area_ratio, sim_->area_ / sim_->area0_);
    s_.max_penetration = std::max(s_.max_penetration, sim_->last_penetration_);
    // Path length inside the medium, with the crossings of y = H and y = 0 interpolated.
    if (!entered_ && cy_ < H_) {
      entered_ = true;
      const double f = (pcy - H_) / (pcy - cy_);
      s_.path_length += distance(pcx + f * (cx_ - pcx), H_, cx_, cy_);
    } else if (entered_) {
      if (cy_ < 0) {
        const double f = pcy / (pcy - cy_);
        s_.path_length += distance(pcx, pcy, pcx + f * (cx_ - pcx), 0);
      } else {
        s_.path_length += distance(pcx, pcy, cx_, cy_);
      }
    }
    record(k);
    if (cy_ < 0) {
      s_.tortuosity = s_.path_length / H_;
      return finish(Outcome::passed, "centre of mass left the medium at y = 0", k);
    }
    if (k % o_.check_interval == 0) {
      if (o_.cancelled && o_.cancelled()) throw RunCancelled{};
      if (ring_self_intersects(sim_->state_))
        return finish(Outcome::diverged, "ring self-intersects at step " + std::to_string(k), k);
      if (sim_->any_grain_inside_ring()) {
        s_.grain_inside_ring = true;
        return finish(Outcome::diverged, "a grain got inside the ring at step " + std::to_string(k), k);
      }
    }
    if (k % window_ == 0) {
      if (checkpoint_y_ - cy_ < o_.stuck_distance) {
        std::ostringstream r;
        r << "centre of mass moved down " << checkpoint_y_ - cy_ << " < " << o_.stuck_distance
          << " in the last " << o_.stuck_window << " time units, at y = " << cy_;
        return finish(Outcome::stuck, r.str(), k);
      }
      checkpoint_y_ = cy_;
    }
    if (rest_window_ > 0) {
      // The centre's travel in any direction: a droplet bouncing off a grain travels far while
      // making no net progress, and is not at rest.
      rest_travel_ += distance(pcx, pcy, cx_, cy_);
      if (k % rest_window_ == 0) {
        if (rest_travel_ < o_.rest_distance) {
          std::ostringstream r;
          r << "at rest: centre of mass travelled " << rest_travel_ << " < " << o_.rest_distance << " in the last "
            << o_.rest_window << " time units, at y = " << cy_;
          return finish(Outcome::stuck, r.str(), k);
        }
        rest_travel_ = 0;
      }
    }
    if (k == o_.max_steps)
      finish(Outcome::timeout, "step budget of " + std::to_string(o_.max_steps) + " steps spent", k);
  }

  RunSummary take() { return std::move(s_); }

 private:
  void record(std::int64_t k) {
    const double t = static_cast<double>(k) * dt_;
    if (o_.path_interval > 0 && k % o_.path_interval == 0) {
      s_.path_t.push_back(t);
      s_.path_x.push_back(cx_);
      s_.path_y.push_back(cy_);
    }
    if (o_.area_interval > 0 && k % o_.area_interval == 0) {
      s_.area_t.push_back(t);
      s_.area.push_back(ring_area(sim_->state_));
    }
    while (next_snapshot_ < snapshot_steps_.size() && snapshot_steps_[next_snapshot_] <= k) {
      s_.snapshots.push_back({t, sim_->state_.x, sim_->state_.y});
      ++next_snapshot_;
    }
  }
  void finish(Outcome o, std::string reason, std::int64_t k) {
    finished_ = true;
    s_.outcome = o;
    s_.reason = std::move(reason);
    s_.steps = k;
    for (std::size_t g = 0; g + 1 < sim_->touched_.size(); ++g)
      if (sim_->touched_[g]) s_.touched.push_back(static_cast<std::int32_t>(g));
    if (o_.path_interval > 0 && (s_.path_t.empty() || s_.path_t.back() != static_cast<double>(k) * dt_)) {
      s_.path_t.push_back(static_cast<double>(k) * dt_);
      s_.path_x.push_back(cx_);
      s_.path_y.push_back(cy_);
    }
  }

  Simulation* sim_;
  const RunOptions& o_;
  RunSummary s_;
  double dt_ = 0, H_ = 0, cx_ = 0, cy_ = 0, checkpoint_y_ = 0, rest_travel_ = 0;
  std::int64_t window_ = 1, rest_window_ = 0, k_ = 0;
  std::vector<std::int64_t> snapshot_steps_;
  std::size_t next_snapshot_ = 0;
  bool entered_ = false, finished_ = false;
};

RunSummary Simulation::run_from_current(const RunOptions& options) {
  RunStepper run(this, options);
  while (!run.finished()) run.after_step(step());
  return run.take();
}

bool Simulation::before_constraint() {
  compute_forces();
  integrate();
  return params_.constraint_order == ConstraintOrder::sequential;
}

bool Simulation::after_constraint() {
  apply_contact_limit();
  return std::isfinite(area_) && area_ > 0;
}

// Droplets of one set of parameters, stepped together on a copy of their positions laid out lane
// by lane (lane_layout.hpp), eight to a group (an AVX-512 register or two AVX ones): forces,
// integration and constraint (either order) as vector code across droplets, where the one-ring
// forms are chains of dependent sums and square roots; the collisions (a grid look-up per mass)
// droplet by droplet on that copy, the contact limit and the run's book-keeping on each droplet's
// own state afterwards. Each lane does the one-ring stages' operations in their order, so every
// droplet gets the bits step() gives it. Its forces stay in the copy: state().fx, fy are not
// updated.
struct LaneBlockStep {
  // Whether droplets of parameters a and b can share a block: the same constants for every stage
  // that runs across lanes (the collisions and the contact limit run droplet by droplet).
  static bool compatible(const DropletParams& a, const DropletParams& b) {
    return a.masses == b.masses && a.constraint_iterations == b.constraint_iterations &&
           a.constraint_order == b.constraint_order && same_bits(a.mass, b.mass) && same_bits(a.radius, b.radius) &&
           same_bits(a.max_strain, b.max_strain) && same_bits(a.nrt, b.nrt) && same_bits(a.ks, b.ks) &&
           same_bits(a.kd, b.kd) && same_bits(a.gravity, b.gravity) && same_bits(a.dt, b.dt) &&
           same_bits(a.viscosity, b.viscosity);
  }
  // The fewest droplets worth a block with `width`; fewer step faster one by one. AVX-512: 3
  // (bench_scenes batch-1lane-1thread: 0.35 M steps/s in a block, 0.38 M alone;
  // search-l2-red-black-1thread with 2 lanes: 54 evaluations/s in blocks, 65 alone; with 3: 67 and
  // 63). AVX, whose groups of eight are two registers each: 6 (run_batch of n droplets on
  // medium-200, microseconds per step of all n in a block / alone: n = 3: 4.63 / 4.36, 4: 5.23 /
  // 4.76, 5: 5.28 / 5.13, 6: 5.54 / 5.71, 8: 5.86 / 6.69).
  static std::size_t fewest(VectorWidth width) { return width == VectorWidth::avx512 ? 3 : 6; }
  // before_constraint() and apply_constraint() (all of step() but the contact limit) for sims[0..count),
  // count <= lanes::kMaxLanes, all compatible with sims[0].
  static void step(Simulation* const* sims, int count);
};

#if defined(SOFTDROP_AVX_DISPATCH)
namespace {
// A thread's block: the lanes' x, y, px, py, fx, fy, and what the last step left in it. After a
// step the first four are each droplet's state (the copy out wrote x, y, and px, py are the
// positions the step began with in both), so a droplet still in the same lane whose state nothing
// has changed since (Simulation::block_id_) need not be copied in again.
struct LaneBlock {
  std::vector<double> data;
  std::uint64_t last_id = 0;  // 0: the data is not a finished step's
  int lanes = 0, count = 0, masses = 0;
};
std::atomic<std::uint64_t> next_block_id{1};  // ids unique over threads: a droplet can change thread
}  // namespace

void LaneBlockStep::step(Simulation* const* sims, int count) {
  const Simulation& first = *sims[0];
  const DropletParams& p = first.params_;
  const int n = first.state_.size();
  const int registers = (count + 7) / 8, L = 8 * registers;
  const std::size_t size = static_cast<std::size_t>(n) * static_cast<std::size_t>(L);
  thread_local LaneBlock memory;
  const bool same_layout = memory.last_id != 0 && memory.lanes == L && memory.masses == n;
  const std::uint64_t previous_id = same_layout ? memory.last_id : 0;
  const bool same_padding = same_layout && memory.count == count;
  memory.last_id = 0;  // until this step has finished
  if (memory.data.size() < 6 * size) memory.data.resize(6 * size);
  double* const X = memory.data.data();
  double* const block[6] = {X, X + size, X + 2 * size, X + 3 * size, X + 4 * size, X + 5 * size};
  double *FX = block[4], *FY = block[5];
  // Padding lanes repeat the last droplet and are not copied back.
  double* in[4][lanes::kMaxLanes];
  double* out[2][lanes::kMaxLanes];
  double* previous[2][lanes::kMaxLanes];
  for (int t = 0; t < L; ++t) {
    DropletState& s = sims[std::min(t, count - 1)]->state_;
    double* const arrays[4] = {s.x.data(), s.y.data(), s.px.data(), s.py.data()};
    for (int a = 0; a < 4; ++a) in[a][t] = arrays[a];
    for (int a = 0; a < 2; ++a) out[a][t] = t < count ? arrays[a] : nullptr;
    for (int a = 0; a < 2; ++a) previous[a][t] = t < count ? arrays[a + 2] : nullptr;
  }
  // The lanes whose droplet is not in the block as the last step left it (padding lanes repeat
  // the last droplet's, and are there if the last step had as many droplets).
  bool stale[lanes::kMaxLanes];
  int stale_lanes = 0;
  for (int t = 0; t < L; ++t) {
    const int d = std::min(t, count - 1);
    const Simulation& sim = *sims[d];
    stale[t] = previous_id == 0 || sim.block_id_ != previous_id || sim.block_lane_ != d ||
               (t >= count && !same_padding);
    stale_lanes += stale[t];
  }
  if (stale_lanes > L / 4) {
    for (int a = 0; a < 4; ++a) lanes::copy_in(in[a], block[a], n, registers);
  } else if (stale_lanes > 0) {
    for (int t = 0; t < L; ++t)
      if (stale[t])
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < n; ++i) block[a][static_cast<std::size_t>(i) * L + t] = in[a][t][i];
  }
  const lanes::StepConstants k = lanes::step_constants(p);
  double area[lanes::kMaxLanes];
  lanes::forces_before_contacts(k, block[0], block[1], block[2], block[3], FX, FY, area, n, registers);
  // The collisions: first the forces the contact limit recorded, for every lane whose droplet's
  // records are current (-0, which changes no double, for the others), then each droplet's own.
  thread_local std::vector<double> no_force;
  if (no_force.size() < static_cast<std::size_t>(n)) no_force.assign(static_cast<std::size_t>(n), -0.0);
  const double* recorded[2][lanes::kMaxLanes];
  for (int t = 0; t < L; ++t) {
    const Simulation& sim = *sims[std::min(t, count - 1)];
    recorded[0][t] = sim.records_current_ ? sim.contact_fx_.data() : no_force.data();
    recorded[1][t] = sim.records_current_ ? sim.contact_fy_.data() : no_force.data();
  }
  lanes::add_in(recorded[0], FX, n, registers);
  lanes::add_in(recorded[1], FY, n, registers);
  for (int t = 0; t < count; ++t) {
    sims[t]->area_ = area[t];
    sims[t]->accumulate_collisions(FX + t, FY + t, L, /*recorded_added=*/true);
  }
  if (p.viscosity > 0) lanes::viscosity(k, block[0], block[1], block[2], block[3], FX, FY, n, registers);
  lanes::integrate(k.h2m, block[0], block[1], block[2], block[3], FX, FY, n, registers);
  const double dmax = (1 + p.max_strain) * first.rest_length_, dmin = (1 - p.max_strain) * first.rest_length_;
  int corrections[lanes::kMaxLanes];
  if (p.constraint_order == ConstraintOrder::sequential)
    lanes::constrain_sequential(block[0], block[1], n, registers, p.constraint_iterations, dmin, dmax, corrections);
  else
    lanes::constrain_red_black(block[0], block[1], n, registers, p.constraint_iterations, dmin, dmax, corrections);
  // Verlet left the positions the step began with as the previous ones, so px, py are x, y as they
  // still are in each state: moved there as the copy out overwrites them, rather than copied back
  // from the block.
  for (int a = 0; a < 2; ++a) lanes::copy_out(out[a], block[a], n, registers, previous[a]);
  const std::uint64_t id = next_block_id.fetch_add(1, std::memory_order_relaxed);
  for (int t = 0; t < count; ++t) {
    sims[t]->block_id_ = id;
    sims[t]->block_lane_ = t;
    sims[t]->records_current_ = false;  // the step moved every mass
  }
  memory.last_id = id;
  memory.lanes = L;
  memory.count = count;
  memory.masses = n;
}
#else
void LaneBlockStep::step(Simulation* const*, int) { throw std::logic_error("lane-by-lane step without AVX"); }
#endif

namespace {

// A lane of run_interleaved: the droplet and its run's book-keeping. (RunStepper holds a reference,
// so lanes move by re-emplacing.)
struct Lane {
  DropletJob job;
  std::optional<RunStepper> run;
};

void move_lane(Lane& from, Lane& to) {
  to.job = from.job;
  to.run.emplace(std::move(*from.run));
  from.run.reset();
}

constexpr int kNoneStarving = 1 << 20;

}  // namespace

// What the threads sharing lanes know of each other: for each seat (a run_interleaved call) how many
// droplets it steps and whether next() left it lanes it could not fill, and one droplet on offer.
struct LaneExchange::Impl {
  struct Seat {
    bool present = true, starving = false;
    int busy = 0;
  };
  std::mutex m;
  std::condition_variable cv;
  std::vector<Seat> seats;
  std::optional<Lane> offer;
  int offer_busy = 0;  // droplets its giver steps without it; only a seat stepping fewer takes it
  int waiting = 0;
  // Read at every step without the lock: the fewest droplets stepped by a starving seat, and
  // whether a droplet is on offer.
  std::atomic<int> min_starving{kNoneStarving};
  std::atomic<bool> offered{false};
  std::atomic<std::int64_t> handovers{0};

  void update_min() {  // under m
    int lo = kNoneStarving;
    for (const Seat& s : seats)
      if (s.present && s.starving) lo = std::min(lo, s.busy);
    min_starving.store(lo, std::memory_order_relaxed);
  }
};

LaneExchange::LaneExchange() : impl_(std::make_unique<Impl>()) {}
LaneExchange::~LaneExchange() = default;
std::int64_t LaneExchange::handovers() const { return impl_->handovers.load(); }

// One run_interleaved call's place at a LaneExchange (none without one: then it does nothing). The
// checks made at every step read two atomics; everything else takes the lock, and happens only when
// a droplet starts, ends or moves.
class LaneExchangeSeat {
 public:
  LaneExchangeSeat(LaneExchange* exchange, int lanes) : x_(exchange ? exchange->impl_.get() : nullptr), lanes_(lanes) {
    if (!x_) return;
    std::lock_guard lock(x_->m);
    seat_ = x_->seats.size();
    x_->seats.emplace_back();
  }
  ~LaneExchangeSeat() {
    if (!x_) return;
    std::lock_guard lock(x_->m);
    x_->seats[seat_] = {false, false, 0};
    x_->update_min();
    x_->cv.notify_all();
  }
  LaneExchangeSeat(const LaneExchangeSeat&) = delete;
  LaneExchangeSeat& operator=(const LaneExchangeSeat&) = delete;

  /// After the lanes are filled: `busy` droplets stepped; lanes left idle mean next() had none.
  void publish(int busy) {
    if (!x_ || busy == busy_) return;
    std::lock_guard lock(x_->m);
    set(busy, busy < lanes_);
  }
  /// Whether a starving thread steps at least two droplets fewer than `busy` and none is on offer.
  bool should_give(int busy) const {
    return x_ && busy >= 2 && !x_->offered.load(std::memory_order_relaxed) &&
           x_->min_starving.load(std::memory_order_relaxed) <= busy - 2;
  }
  /// Offers the droplet in `lane` (this thread steps `busy` with it); false if that no longer fits.
  bool give(Lane& lane, int busy) {
    std::lock_guard lock(x_->m);
    if (x_->offer || x_->min_starving.load(std::memory_order_relaxed) > busy - 2) return false;
    x_->offer.emplace();
    move_lane(lane, *x_->offer);
    x_->offer_busy = busy - 1;
    x_->offered.store(true, std::memory_order_relaxed);
    set(busy - 1, busy - 1 < lanes_);
    x_->cv.notify_all();
    return true;
  }
  bool offer_waiting() const { return x_ && x_->offered.load(std::memory_order_relaxed); }
  /// Takes the droplet on offer into the idle `lane` if its giver steps more than `busy`, the
  /// droplets this thread steps without it (so a giver does not take its offer back).
  bool take(Lane& lane, int busy) {
    if (!x_) return false;
    std::lock_guard lock(x_->m);
    return take_locked(lane, busy);
  }
  /// With every lane idle, before next() may wait: takes a droplet on offer, or else says this
  /// thread starves no more, so that none is offered to it while it waits in next().
  bool take_or_withdraw(Lane& lane) {
    if (!x_) return false;
    std::lock_guard lock(x_->m);
    if (take_locked(lane, 0)) return true;
    set(0, false);
    return false;
  }
  /// With every lane idle and next() out of droplets: waits for a droplet on offer; false once no
  /// other thread steps two or more (none will be offered).
  bool wait_for_offer(Lane& lane) {
    if (!x_) return false;
    std::unique_lock lock(x_->m);
    set(0, true);
    ++x_->waiting;
    x_->cv.wait(lock, [&] {
      if (x_->offer) return true;
      for (std::size_t i = 0; i < x_->seats.size(); ++i)
        if (i != seat_ && x_->seats[i].present && x_->seats[i].busy >= 2) return false;
      return true;
    });
    --x_->waiting;
    return take_locked(lane, 0);
  }

 private:
  void set(int busy, bool starving) {  // under the lock
    busy_ = busy;
    x_->seats[seat_].busy = busy;
    x_->seats[seat_].starving = starving;
    x_->update_min();
    if (x_->waiting > 0) x_->cv.notify_all();
  }
  bool take_locked(Lane& lane, int busy) {
    if (!x_->offer || busy >= x_->offer_busy) return false;
    move_lane(*x_->offer, lane);
    x_->offer.reset();
    x_->offered.store(false, std::memory_order_relaxed);
    x_->handovers.fetch_add(1, std::memory_order_relaxed);
    set(busy + 1, busy + 1 < lanes_);
    return true;
  }

  LaneExchange::Impl* x_;
  const int lanes_;
  std::size_t seat_ = 0;
  int busy_ = 0;  // as last published
};

namespace {
// Simulation::centre_of_mass of sims[0..count): four droplets' ordered sums side by side where
// they have the same number of masses (each sum's additions in its own order, so the same bits),
// so that the processor overlaps their chains of dependent additions instead of waiting out each
// (sweep-long: 4 % of the time in those chains one droplet at a time).
void centres_of_mass(Simulation* const* sims, int count, double* cx, double* cy) {
  int t = 0;
  for (; t + 4 <= count; t += 4) {
    const DropletState* s[4] = {&sims[t]->state(), &sims[t + 1]->state(), &sims[t + 2]->state(), &sims[t + 3]->state()};
    const int n = s[0]->size();
    if (s[1]->size() != n || s[2]->size() != n || s[3]->size() != n) {
      for (int k = 0; k < 4; ++k) sims[t + k]->centre_of_mass(cx + t + k, cy + t + k);
      continue;
    }
    double x0 = 0, x1 = 0, x2 = 0, x3 = 0, y0 = 0, y1 = 0, y2 = 0, y3 = 0;
    for (int i = 0; i < n; ++i) {
      x0 += s[0]->x[i], x1 += s[1]->x[i], x2 += s[2]->x[i], x3 += s[3]->x[i];
      y0 += s[0]->y[i], y1 += s[1]->y[i], y2 += s[2]->y[i], y3 += s[3]->y[i];
    }
    const double sums_x[4] = {x0, x1, x2, x3}, sums_y[4] = {y0, y1, y2, y3};
    for (int k = 0; k < 4; ++k) cx[t + k] = sums_x[k] / n, cy[t + k] = sums_y[k] / n;
  }
  for (; t < count; ++t) sims[t]->centre_of_mass(cx + t, cy + t);
}
}  // namespace

int interleaved_lanes() {
  // Blocks of three groups: sweep-long-1thread with AVX, 1.47 M steps/s at 8 and 12 lanes, 1.72 M
  // at 16, 1.69 M at 24.
  return constraint_vector_width() >= VectorWidth::avx ? lanes::kMaxLanes : interleaved_ring_capacity();
}

void run_interleaved(int lanes, const std::function<bool(DropletJob*, bool may_wait)>& next,
                     const std::function<void(std::int64_t id, RunSummary&&)>& done,
                     const std::function<void(std::int64_t id)>& cancelled, LaneExchange* exchange) {
  if (lanes < 1 || lanes > 64) throw std::invalid_argument("lanes = " + std::to_string(lanes) + ": must be in [1, 64]");
  std::vector<Lane> slots(static_cast<std::size_t>(lanes));
  std::vector<DropletState*> rings;
  std::vector<int> corrections;
  std::vector<Simulation*> block, alone, stepped;
  std::vector<double> cx(static_cast<std::size_t>(lanes)), cy(cx.size());
  std::vector<char> valid(cx.size());
  const VectorWidth width = constraint_vector_width();
  const bool lane_wise = width >= VectorWidth::avx;
  LaneExchangeSeat seat(exchange, lanes);
  int busy = 0;
  auto idle_lane = [&]() -> Lane& {
    for (Lane& l : slots)
      if (!l.run) return l;
    throw std::logic_error("run_interleaved: no idle lane");
  };
  // Fills idle lanes; may wait only while every lane is idle, and then a refusal means "no more".
  auto fill = [&](bool may_wait) {
    for (Lane& l : slots) {
      if (l.run) continue;
      if (!next(&l.job, may_wait && busy == 0)) return;
      l.job.sim->place_above(l.job.x0);
      l.run.emplace(l.job.sim, *l.job.options);
      ++busy;
    }
  };
  for (;;) {
    fill(false);
    if (busy < lanes && seat.offer_waiting() && seat.take(idle_lane(), busy)) ++busy;
    if (busy == 0) {
      if (seat.take_or_withdraw(idle_lane())) {
        ++busy;
      } else {
        fill(true);
        if (busy == 0) {
          if (!seat.wait_for_offer(idle_lane())) return;
          ++busy;
        }
      }
    }
    seat.publish(busy);
    if (seat.should_give(busy)) {
      for (auto l = slots.rbegin(); l != slots.rend(); ++l)
        if (l->run) {
          if (seat.give(*l, busy)) --busy;
          break;
        }
    }
    // One step of every busy lane. With AVX-512 or AVX, the droplets with the first one's
    // parameters go lane by lane up to the contact limit (LaneBlockStep) if there are at least
    // fewest(); the others, and all with SSE2 alone:
    // forces and integration each, the sequential constraints of the rings that share the first
    // one's constraint parameters together. Then the contact limits.
    block.clear();
    alone.clear();
    for (Lane& l : slots) {
      if (!l.run) continue;
      Simulation* sim = l.run->simulation();
      if (lane_wise && (block.empty() || LaneBlockStep::compatible(block.front()->params(), sim->params())))
        block.push_back(sim);
      else
        alone.push_back(sim);
    }
    if (block.size() < LaneBlockStep::fewest(width)) {
      alone.insert(alone.end(), block.begin(), block.end());
      block.clear();
    }
    rings.clear();
    const Simulation* first = nullptr;
    for (Simulation* sim : alone) {
      if (sim->before_constraint()) {
        if (!first) first = sim;
        const DropletParams &a = first->params(), &b = sim->params();
        if (a.masses == b.masses && a.radius == b.radius && a.max_strain == b.max_strain &&
            a.constraint_iterations == b.constraint_iterations) {
          rings.push_back(&sim->mutable_state());
          continue;
        }
      }
      sim->apply_constraint();
    }
    if (!rings.empty()) {
      corrections.resize(rings.size());
      apply_length_constraint_interleaved(rings.data(), static_cast<int>(rings.size()), first->rest_length(),
                                          first->params().max_strain, first->params().constraint_iterations,
                                          corrections.data());
    }
    // Blocks of nearly equal size: 25 droplets go as 13 and 12, not 24 and 1.
    const std::size_t blocks = (block.size() + lanes::kMaxLanes - 1) / lanes::kMaxLanes;
    for (std::size_t b = 0, begin = 0; b < blocks; ++b) {
      const std::size_t end = block.size() * (b + 1) / blocks;
      LaneBlockStep::step(block.data() + begin, static_cast<int>(end - begin));
      begin = end;
    }
    // The contact limits, then every lane's centre of mass at once, then each run's book-keeping.
    stepped.clear();
    for (Lane& l : slots) {
      if (!l.run) continue;
      valid[stepped.size()] = l.run->simulation()->after_constraint();
      stepped.push_back(l.run->simulation());
    }
    centres_of_mass(stepped.data(), static_cast<int>(stepped.size()), cx.data(), cy.data());
    std::size_t t = 0;
    for (Lane& l : slots) {
      if (!l.run) continue;
      const bool ok = valid[t] != 0;
      const double x = cx[t], y = cy[t];
      ++t;
      if (cancelled) {
        try {
          l.run->after_step(ok, x, y);
        } catch (const RunCancelled&) {
          l.run.reset();
          --busy;
          cancelled(l.job.id);
          continue;
        }
      } else {
        l.run->after_step(ok, x, y);
      }
      if (l.run->finished()) {
        RunSummary summary = l.run->take();
        l.run.reset();
        --busy;
        done(l.job.id, std::move(summary));
      }
    }
  }
}

std::uint64_t Simulation::state_hash() const {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const std::vector<double>& v) {
    for (double d : v) {
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      for (int b = 0; b < 8; ++b) {
        h ^= (bits >> (8 * b)) & 0xFF;
        h *= 1099511628211ULL;
      }
    }
  };
  mix(state_.x);
  mix(state_.y);
  mix(state_.px);
  mix(state_.py);
  return h;
}

double polyline_tortuosity(const std::vector<double>& xs, const std::vector<double>& ys, double top) {
  double length = 0;
  bool entered = false;
  for (std::size_t k = 1; k < xs.size(); ++k) {
    const double ax = xs[k - 1], ay = ys[k - 1], bx = xs[k], by = ys[k];
    if (!entered) {
      if (ay >= top && by < top) {
        entered = true;
        const double f = (ay - top) / (ay - by);
        if (by < 0) {
          const double g = ay / (ay - by);
          return distance(ax + f * (bx - ax), top, ax + g * (bx - ax), 0) / top;
        }
        length += distance(ax + f * (bx - ax), top, bx, by);
      }
      continue;
    }
    if (by < 0) {
      const double f = ay / (ay - by);
      return (length + distance(ax, ay, ax + f * (bx - ax), 0)) / top;
    }
    length += distance(ax, ay, bx, by);
  }
  return 0;
}

}  // namespace softdrop
