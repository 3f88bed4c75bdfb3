// The force stages of a droplet's step: gravity, springs, gas pressure, collisions with the
// grains and internal viscosity: the first five stages of kStepStages (step_stages.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "contact_lanes.hpp"
#include "lane_layout.hpp"
#include "lane_policy.hpp"
#include "lane_scalar.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/simulation.hpp"
#include "step_context.hpp"
#include "step_helpers.hpp"

namespace softdrop {

using step_detail::same_bits;
using step_detail::within_walls;
using step_detail::wrap_periodic;

void Simulation::accumulate_gravity() {
  const double w = context_->weight;
  std::fill(state_.fx.begin(), state_.fx.end(), 0.0);
  std::fill(state_.fy.begin(), state_.fy.end(), w);
}

void Simulation::accumulate_springs() {
  // Two passes: the force of every spring (independent; eight at a time with AVX or AVX-512, the
  // kernel the lane-by-lane step uses, where constraint_vector_width() allows), then each mass
  // gathers its two springs in the order of the scalar loop "for each spring i: f[i] += s,
  // f[i+1] -= s" (mass m >= 1: (f - s[m-1]) + s[m]; mass 0: (f + s[0]) - s[n-1]), so the sums
  // have the same bits.
  const int n = state_.size();
  const StepContext& in = *context_;
  const std::size_t un = static_cast<std::size_t>(n);
  if (spring_force_.size() != 4 * un) spring_force_.assign(4 * un, 0.0);
  double* plus_x = spring_force_.data();  // added to the first end; -0 if the spring has no length
  double* plus_y = plus_x + un;
  double* minus_x = plus_y + un;  // subtracted from the second end; +0 then
  double* minus_y = minus_x + un;
  double* fx = state_.fx.data();
  double* fy = state_.fy.data();
  const double *x = state_.x.data(), *y = state_.y.data();
  const double *px = state_.px.data(), *py = state_.py.data();
  int i = 0;
#if defined(SOFTDROP_AVX_DISPATCH)
  if (constraint_vector_width() >= VectorWidth::avx && n >= 9) {
    lanes::ring_spring_forces(in, x, y, px, py, n, plus_x, plus_y, minus_x, minus_y);
    i = n - 1;
  }
#endif
  // The rest (the closing spring, or every spring without AVX): the same kernel on one lane.
  const lanes::scalar::SpringConstants springs = lanes::scalar::spring_constants(in);
  for (; i < n; ++i) {
    const int j = i + 1 == n ? 0 : i + 1;
    const lanes::scalar::SpringForce s =
        lanes::scalar::spring_force(springs, x[i], y[i], x[j], y[j], px[i], py[i], px[j], py[j]);
    plus_x[i] = s.plus_x;
    plus_y[i] = s.plus_y;
    minus_x[i] = s.minus_x;
    minus_y[i] = s.minus_y;
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
  // Edge i's force (the kernel of stage_kernels.inc at width 1), half to each of its ends. Each
  // mass gathers its two edges in the order of the loop "for each edge i: f[i] += e, f[i+1] += e":
  // mass m >= 1 adds e[m-1] then e[m]; mass 0 adds e[0] then e[n-1]. (An inner edge is computed
  // for each of its ends, which keeps the loop free of a carried value.)
  const double half_p = context_->half_nrt / area_, minus_half_p = -half_p;
  double* fx = state_.fx.data();
  double* fy = state_.fy.data();
  const double *x = state_.x.data(), *y = state_.y.data();
  const auto edge = [&](int i, int j) {
    return lanes::scalar::edge_pressure(half_p, minus_half_p, x[j] - x[i], y[j] - y[i]);
  };
  const lanes::scalar::EdgeForce first = edge(0, 1), last = edge(n - 1, 0);
  for (int m = 1; m + 1 < n; ++m) {
    const lanes::scalar::EdgeForce before = edge(m - 1, m), after = edge(m, m + 1);
    fx[m] = (fx[m] + before.x) + after.x;
    fy[m] = (fy[m] + before.y) + after.y;
  }
  const lanes::scalar::EdgeForce before_last = edge(n - 2, n - 1);
  fx[n - 1] = (fx[n - 1] + before_last.x) + last.x;
  fy[n - 1] = (fy[n - 1] + before_last.y) + last.y;
  fx[0] = (fx[0] + first.x) + last.x;
  fy[0] = (fy[0] + first.y) + last.y;
}

void Simulation::accumulate_collisions() { accumulate_collisions(state_.fx.data(), state_.fy.data(), 1); }

void Simulation::accumulate_collisions(double* fx, double* fy, std::ptrdiff_t stride, bool recorded_added) {
  const int n = state_.size();
  const double kc = params_.kc, cc = params_.cc, inv_dt = 1.0 / params_.dt;
  const double W = medium_.width;
  const bool periodic = medium_.periodic;
  double deepest = 0;
  // The arrays as locals: the touched set's byte stores may alias anything, and would otherwise
  // make the compiler reload every vector's data pointer after each of them.
  const double *xs = state_.x.data(), *ys = state_.y.data(), *pxs = state_.px.data(), *pys = state_.py.data();
  const double *cxs = contact_.x.data(), *cys = contact_.y.data();
  const std::int32_t* counts = contact_.count.data();
  const GrainGrid::Disc* const contacts = contact_.discs.data();
  const double *first_x = contact_.disc_x.data(), *first_y = contact_.disc_y.data(), *first_r = contact_.disc_r.data();
  const std::int32_t* first_grain = contact_.disc_grain.data();
  const std::size_t capacity = contact_.capacity;
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
  if (contact_.current) {
    // The contact limit left the forces of the masses inside one disc (-0 for the others, which
    // changes no double), their grains and their largest depth, at these very positions and
    // velocities: every mass gets its force with no test, and those it did not cover are listed.
    contact_.current = false;
    const double *force_x = contact_.fx.data(), *force_y = contact_.fy.data();
    if (!recorded_added) {
      for (int i = 0; i < n; ++i) {
        fx[i * stride] += force_x[i];
        fy[i * stride] += force_y[i];
      }
    }
    const std::int32_t* touch = contact_.touch.data();
    for (int i = 0; i < n; ++i) touched[static_cast<std::size_t>(touch[i])] = 1;
    deepest = contact_.deepest;  // the maximum does not depend on the order of the masses
    for (const std::int32_t i : contact_.todo) collide_mass(i);
  } else {
    for (int i = 0; i < n; ++i) {
      // Most masses touch nothing: recorded inside no disc, and within the walls.
      const double x = xs[i], y = ys[i];
      if (same_bits(x, cxs[i]) && same_bits(y, cys[i]) && counts[i] == 0 && within_walls(x, periodic, W)) continue;
      collide_mass(i);
    }
  }
  last_penetration_ = deepest;
}

void Simulation::accumulate_viscosity() {
  // Rigid motion of the ring from its linear and angular momentum; the viscous force acts on the
  // rest, so it sums to zero force and zero torque (the lane block's kernel, at width 1).
  const StepContext& k = *context_;
  lanes::scalar::viscosity_k<1>(k, state_.x.data(), state_.y.data(), state_.px.data(), state_.py.data(),
                                state_.fx.data(), state_.fy.data(), state_.size());
}

}  // namespace softdrop
