// The contact limit, the last stage of a step: no mass stays deeper than max_depth inside a grain.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "contact_lanes.hpp"
#include "lane_policy.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/simulation.hpp"
#include "step_helpers.hpp"

namespace softdrop {

using step_detail::within_walls;
using step_detail::wrap_periodic;

void Simulation::apply_contact_limit() {
  // Inverse dynamics for contacts: no mass stays deeper than max_depth inside a grain, and one
  // that is pushed back loses the normal velocity that carried it in (an inelastic stop).
  const int n = state_.size();
  const double W = medium_.width, limit = params_.max_depth;
  const bool periodic = medium_.periodic;
  const std::size_t capacity = contact_.capacity;
  const auto first_contact = [this](int i, const GrainGrid::Disc& g) {
    contact_.disc_x[i] = g.x;
    contact_.disc_y[i] = g.y;
    contact_.disc_r[i] = g.r;
    contact_.disc_grain[i] = g.grain;
  };
  const std::int32_t no_grain = static_cast<std::int32_t>(medium_.grains.size());
  contact_.current = false;
  contact_.todo.clear();
  alignas(64) double deepest[8] = {};  // of the forces recorded, lane by lane
  // The next collisions of a mass tested here, not eight at a time: no recorded force, and a
  // full look at its record unless it is recorded free within the walls.
  const auto leave_to_collisions = [&](int i, double x, bool free) {
    contact_.fx[i] = -0.0;
    contact_.fy[i] = -0.0;
    contact_.touch[i] = no_grain;
    if (!(free && within_walls(x, periodic, W))) contact_.todo.push_back(i);
  };
  const auto limit_mass = [&](int i) {
    const double x = state_.x[i], y = state_.y[i];
    const std::size_t first = static_cast<std::size_t>(i) * capacity;
    GrainGrid::Disc* inside = contact_.discs.data() + first;
    // Within its ball only the anchor's discs can hold or push the mass, and each test of the
    // others below would say so: test those discs alone, in the cell's order.
    const double ex = x - contact_.clear_x[i], ey = y - contact_.clear_y[i];
    if (ex * ex + ey * ey < contact_.clear_r2[i]) {
      const int anchored = contact_.clear_count[i];
      int count = 0;
      bool push = false;
      if (anchored > 0) {
        const double xw = periodic ? wrap_periodic(x, W) : x;
        for (const GrainGrid::Disc *g = contact_.clear_discs.data() + first, *end = g + anchored; g != end; ++g) {
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
        contact_.count[i] = count;
        contact_.x[i] = x;
        contact_.y[i] = y;
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
    contact_.count[i] = recorded ? count : 0;
    contact_.x[i] = recorded ? x : std::numeric_limits<double>::quiet_NaN();
    contact_.y[i] = y;
    leave_to_collisions(i, x, recorded && count == 0);
    // No disc outside the cell's list is nearer than the cell's edge plus the grid's halo; the ball
    // must not cross the periodic seam either, where the wrapped position jumps.
    double reach = std::min(gap, grid_.edge_distance(xw, y));
    if (periodic) reach = std::min(reach, std::min(xw, W - xw));
    reach -= contact_.clearance_margin;
    const bool anchored = recorded && reach > 0;
    contact_.clear_r2[i] = anchored ? reach * reach : -1.0;
    contact_.clear_x[i] = x;
    contact_.clear_y[i] = y;
    contact_.clear_count[i] = anchored ? count : 0;
    if (anchored) std::copy(inside, inside + count, contact_.clear_discs.begin() + static_cast<std::ptrdiff_t>(first));
  };
  int i = 0;
#if defined(SOFTDROP_AVX_DISPATCH)
  if (constraint_vector_width() >= VectorWidth::avx) {
    // Eight masses at a time: most are in their balls, free or inside their anchor's one disc. The
    // vector code reads plain arrays (contact_lanes.hpp), so each field is set here, once.
    lanes::ContactRecords r;
    r.x = state_.x.data();
    r.y = state_.y.data();
    r.clear_x = contact_.clear_x.data();
    r.clear_y = contact_.clear_y.data();
    r.clear_r2 = contact_.clear_r2.data();
    r.clear_count = contact_.clear_count.data();
    r.disc_x = contact_.disc_x.data();
    r.disc_y = contact_.disc_y.data();
    r.disc_r = contact_.disc_r.data();
    r.contact_x = contact_.x.data();
    r.contact_y = contact_.y.data();
    r.contact_count = contact_.count.data();
    r.disc_grain = contact_.disc_grain.data();
    r.no_grain = no_grain;
    r.px = state_.px.data();
    r.py = state_.py.data();
    r.kc = params_.kc;
    r.cc = params_.cc;
    r.inv_dt = 1.0 / params_.dt;
    r.force_x = contact_.fx.data();
    r.force_y = contact_.fy.data();
    r.touch = contact_.touch.data();
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
  contact_.deepest = *std::max_element(deepest, deepest + 8);
  contact_.current = true;
}

}  // namespace softdrop
