// The contact limit, the last stage of a step: no mass stays deeper than max_depth inside a grain.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "contact_lanes.hpp"
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
        for (const GrainGrid::Disc *g = clear_discs_.data() + first, *end = g + anchored; g != end;
             ++g) {
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
    if (anchored)
      std::copy(inside, inside + count, clear_discs_.begin() + static_cast<std::ptrdiff_t>(first));
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
        for (unsigned left = todo[g]; left != 0; left &= left - 1)
          limit_mass(i + std::countr_zero(left));
    }
  }
#endif
  for (; i < n; ++i) limit_mass(i);
  // The maximum does not depend on the order.
  contact_deepest_ = *std::max_element(deepest, deepest + 8);
  records_current_ = true;
}

}  // namespace softdrop
