// The force stages of a droplet's step: gravity, springs, gas pressure, collisions with the
// grains and internal viscosity: the first five stages of kStepStages (step_stages.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "contact_limit_wide.hpp"
#include "image_contacts.hpp"
#include "lane_layout.hpp"
#include "lane_policy.hpp"
#include "lane_scalar.hpp"
#include "ring_stages.hpp"
#include "simd_dispatch.hpp"
#include "step_context.hpp"
#include "step_helpers.hpp"

namespace softdrop {

using step_detail::same_bits;
using step_detail::within_walls;
using step_detail::wrap_periodic;

void gravity_stage(const DropletModel& m, DropletRuntime& r) {
  const double w = m.context.weight;
  std::fill(r.state.fx.begin(), r.state.fx.end(), 0.0);
  std::fill(r.state.fy.begin(), r.state.fy.end(), w);
}

void vibration_stage(const DropletModel&, DropletRuntime& r) {
  // The additions of the lane block's add_in, one lane.
  const std::size_t n = r.state.fx.size();
  for (std::size_t i = 0; i < n; ++i) {
    r.state.fx[i] += r.shake.fx[i];
    r.state.fy[i] += r.shake.fy[i];
  }
}

void springs_stage(const DropletModel& m, DropletRuntime& r) {
  // Two passes: the force of every spring (independent; eight at a time with AVX or AVX-512, the
  // kernel the lane-by-lane step uses, where constraint_vector_width() allows), then each mass
  // gathers its two springs in the order of the scalar loop "for each spring i: f[i] += s,
  // f[i+1] -= s" (mass m >= 1: (f - s[m-1]) + s[m]; mass 0: (f + s[0]) - s[n-1]), so the sums
  // have the same bits.
  const int n = r.state.size();
  const StepContext& in = m.context;
  const std::size_t un = static_cast<std::size_t>(n);
  if (r.spring_force.size() != 4 * un) r.spring_force.assign(4 * un, 0.0);
  double* plus_x = r.spring_force.data();  // added to the first end; -0 if the spring has no length
  double* plus_y = plus_x + un;
  double* minus_x = plus_y + un;  // subtracted from the second end; +0 then
  double* minus_y = minus_x + un;
  double* fx = r.state.fx.data();
  double* fy = r.state.fy.data();
  const double *x = r.state.x.data(), *y = r.state.y.data();
  const double *px = r.state.px.data(), *py = r.state.py.data();
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
  for (int mass = 1; mass < n; ++mass) {
    fx[mass] = (fx[mass] - minus_x[mass - 1]) + plus_x[mass];
    fy[mass] = (fy[mass] - minus_y[mass - 1]) + plus_y[mass];
  }
}

void pressure_stage(const DropletModel& m, DropletRuntime& r) {
  r.area = ring_area(r.state);
  const int n = r.state.size();
  // Edge i's force (the kernel of stage_kernels.inc at width 1), half to each of its ends. Each
  // mass gathers its two edges in the order of the loop "for each edge i: f[i] += e, f[i+1] += e":
  // mass m >= 1 adds e[m-1] then e[m]; mass 0 adds e[0] then e[n-1]. (An inner edge is computed
  // for each of its ends, which keeps the loop free of a carried value.)
  const double half_p = m.context.half_nrt / r.area, minus_half_p = -half_p;
  double* fx = r.state.fx.data();
  double* fy = r.state.fy.data();
  const double *x = r.state.x.data(), *y = r.state.y.data();
  const auto edge = [&](int i, int j) {
    return lanes::scalar::edge_pressure(half_p, minus_half_p, x[j] - x[i], y[j] - y[i]);
  };
  const lanes::scalar::EdgeForce first = edge(0, 1), last = edge(n - 1, 0);
  for (int mass = 1; mass + 1 < n; ++mass) {
    const lanes::scalar::EdgeForce before = edge(mass - 1, mass), after = edge(mass, mass + 1);
    fx[mass] = (fx[mass] + before.x) + after.x;
    fy[mass] = (fy[mass] + before.y) + after.y;
  }
  const lanes::scalar::EdgeForce before_last = edge(n - 2, n - 1);
  fx[n - 1] = (fx[n - 1] + before_last.x) + last.x;
  fy[n - 1] = (fy[n - 1] + before_last.y) + last.y;
  fx[0] = (fx[0] + first.x) + last.x;
  fy[0] = (fy[0] + first.y) + last.y;
}

void collisions_stage(const DropletModel& m, DropletRuntime& r, double* fx, double* fy, std::ptrdiff_t stride,
                      bool recorded_added) {
  if (m.field) {
    image_collisions(m, r, fx, fy, stride);
    return;
  }
  const int n = r.state.size();
  const double kc = m.params.kc, cc = m.params.cc, inv_dt = 1.0 / m.params.dt;
  const double W = m.medium.width;
  const bool periodic = m.medium.periodic;
  double deepest = 0;
  // The arrays as locals: the touched set's byte stores may alias anything, and would otherwise
  // make the compiler reload every vector's data pointer after each of them.
  const double *xs = r.state.x.data(), *ys = r.state.y.data(), *pxs = r.state.px.data(), *pys = r.state.py.data();
  const double *cxs = r.contact.x.data(), *cys = r.contact.y.data();
  const std::int32_t* counts = r.contact.count.data();
  const GrainGrid::Disc* const contacts = r.contact.discs.data();
  const double *first_x = r.contact.disc_x.data(), *first_y = r.contact.disc_y.data(),
               *first_r = r.contact.disc_r.data();
  const std::int32_t* first_grain = r.contact.disc_grain.data();
  const std::size_t capacity = r.contact.capacity;
  std::uint8_t* const touched = r.touched.data();
  // Mass i's contacts, for any mass but one recorded free within the walls.
  const auto collide_mass = [&](int i) {
    const double x = xs[i], y = ys[i];
    const bool recorded = same_bits(x, cxs[i]) && same_bits(y, cys[i]);
    const double vx = (x - pxs[i]) * inv_dt, vy = (y - pys[i]) * inv_dt;
    const double xw = periodic ? wrap_periodic(x, W) : x;
    // Penalty spring from the surface point plus damping of the normal velocity; never pulls.
    const auto collide = [&](double gx, double gy, double gr, std::int32_t grain) {
      const double dx = xw - gx, dy = y - gy;
      const double d2 = dx * dx + dy * dy;
      if (d2 >= gr * gr) return;
      const double d = std::sqrt(d2);
      const double nx = d > 0 ? dx / d : 0.0, ny = d > 0 ? dy / d : 1.0, depth = gr - d;
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
      const auto range = recorded ? GrainGrid::DiscRange{record, record + counts[i]} : m.grid.discs_near(xw, y);
      for (const GrainGrid::Disc* g = range.begin; g != range.end; ++g) collide(g->x, g->y, g->r, g->grain);
    }
    if (!periodic) {  // solid side walls
      if (x < 0) fx[i * stride] += std::max(0.0, -kc * x - cc * vx);
      if (x > W) fx[i * stride] -= std::max(0.0, kc * (x - W) + cc * vx);
    }
  };
  if (r.contact.current) {
    // The contact limit left the forces of the masses inside one disc (-0 for the others, which
    // changes no double), their grains and their largest depth, at these very positions and
    // velocities: every mass gets its force with no test, and those it did not cover are listed.
    r.contact.current = false;
    const double *force_x = r.contact.fx.data(), *force_y = r.contact.fy.data();
    if (!recorded_added) {
      for (int i = 0; i < n; ++i) {
        fx[i * stride] += force_x[i];
        fy[i * stride] += force_y[i];
      }
    }
    const std::int32_t* touch = r.contact.touch.data();
    for (int i = 0; i < n; ++i) touched[static_cast<std::size_t>(touch[i])] = 1;
    deepest = r.contact.deepest;  // the maximum does not depend on the order of the masses
    for (const std::int32_t i : r.contact.todo) collide_mass(i);
  } else {
    for (int i = 0; i < n; ++i) {
      // Most masses touch nothing: recorded inside no disc, and within the walls.
      const double x = xs[i], y = ys[i];
      if (same_bits(x, cxs[i]) && same_bits(y, cys[i]) && counts[i] == 0 && within_walls(x, periodic, W)) continue;
      collide_mass(i);
    }
  }
  r.last_penetration = deepest;
}

void viscosity_stage(const DropletModel& m, DropletRuntime& r) {
  // Rigid motion of the ring from its linear and angular momentum; the viscous force acts on the
  // rest, so it sums to zero force and zero torque (the lane block's kernel, at width 1).
  const StepContext& k = m.context;
  lanes::scalar::viscosity_k<1>(k, r.state.x.data(), r.state.y.data(), r.state.px.data(), r.state.py.data(),
                                r.state.fx.data(), r.state.fy.data(), r.state.size());
}

}  // namespace softdrop
