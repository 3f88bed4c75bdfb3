// The contact limit, the last stage of a step: no mass stays deeper than max_depth inside a grain.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "contact_limit_wide.hpp"
#include "image_contacts.hpp"
#include "lane_policy.hpp"
#include "ring_stages.hpp"
#include "simd_dispatch.hpp"
#include "step_helpers.hpp"

namespace softdrop {

using step_detail::within_walls;
using step_detail::wrap_periodic;

void contact_limit_stage(const DropletModel& m, DropletRuntime& r) {
  if (m.field) {
    image_contact_limit(m, r);
    return;
  }
  // Inverse dynamics for contacts: no mass stays deeper than max_depth inside a grain, and one
  // that is pushed back loses the normal velocity that carried it in (an inelastic stop).
  const int n = r.state.size();
  const double W = m.medium.width, limit = m.params.max_depth;
  const bool periodic = m.medium.periodic;
  const std::size_t capacity = r.contact.capacity;
  const auto first_contact = [&r](int i, const GrainGrid::Disc& g) {
    r.contact.disc_x[i] = g.x;
    r.contact.disc_y[i] = g.y;
    r.contact.disc_r[i] = g.r;
    r.contact.disc_grain[i] = g.grain;
  };
  const std::int32_t no_grain = m.obstacles;
  r.contact.current = false;
  r.contact.todo.clear();
  alignas(64) double deepest[8] = {};  // of the forces recorded, lane by lane
  // The next collisions of a mass tested here, not eight at a time: no recorded force, and a
  // full look at its record unless it is recorded free within the walls.
  const auto leave_to_collisions = [&](int i, double x, bool free) {
    r.contact.fx[i] = -0.0;
    r.contact.fy[i] = -0.0;
    r.contact.touch[i] = no_grain;
    if (!(free && within_walls(x, periodic, W))) r.contact.todo.push_back(i);
  };
  const auto limit_mass = [&](int i) {
    const double x = r.state.x[i], y = r.state.y[i];
    const std::size_t first = static_cast<std::size_t>(i) * capacity;
    GrainGrid::Disc* inside = r.contact.discs.data() + first;
    // Within its ball only the anchor's discs can hold or push the mass, and each test of the
    // others below would say so: test those discs alone, in the cell's order.
    const double ex = x - r.contact.clear_x[i], ey = y - r.contact.clear_y[i];
    if (ex * ex + ey * ey < r.contact.clear_r2[i]) {
      const int anchored = r.contact.clear_count[i];
      int count = 0;
      bool push = false;
      if (anchored > 0) {
        const double xw = periodic ? wrap_periodic(x, W) : x;
        for (const GrainGrid::Disc *g = r.contact.clear_discs.data() + first, *end = g + anchored; g != end; ++g) {
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
        r.contact.count[i] = count;
        r.contact.x[i] = x;
        r.contact.y[i] = y;
        leave_to_collisions(i, x, count == 0);
        return;
      }
    }
    const double xw = periodic ? wrap_periodic(x, W) : x;
    const std::int64_t cell = m.grid.cell_of(xw, y);
    const auto range = m.grid.discs_in(cell);
    // The discs the mass is inside, tested as collisions_stage will test them next step,
    // and how far it is from the surface of the nearest other one.
    int count = 0;
    double gap = std::numeric_limits<double>::infinity();
    bool pushed = false;
    for (const GrainGrid::Disc* g = range.begin; g != range.end; ++g) {
      const double dx = xw - g->x, dy = r.state.y[i] - g->y, inner = g->r - limit;
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
      const double vx = r.state.x[i] - r.state.px[i], vy = r.state.y[i] - r.state.py[i];
      const double vn = std::min(0.0, vx * nx + vy * ny);  // inward displacement per step
      r.state.x[i] += push * nx;
      r.state.y[i] += push * ny;
      r.state.px[i] = r.state.x[i] - (vx - vn * nx);
      r.state.py[i] = r.state.y[i] - (vy - vn * ny);
      pushed = true;
      r.block.id = 0;
    }
    // A pushed mass has moved since the tests, and one inside too many discs has no full record:
    // their collisions look them up again, and they get no anchor. (A NaN position that matches
    // the marker finds no discs either way.)
    const bool recorded = !pushed && static_cast<std::size_t>(count) <= capacity;
    r.contact.count[i] = recorded ? count : 0;
    r.contact.x[i] = recorded ? x : std::numeric_limits<double>::quiet_NaN();
    r.contact.y[i] = y;
    leave_to_collisions(i, x, recorded && count == 0);
    // No disc outside the cell's list is nearer than the cell's edge plus the grid's halo; the ball
    // must not cross the periodic seam either, where the wrapped position jumps.
    double reach = std::min(gap, m.grid.edge_distance(xw, y));
    if (periodic) reach = std::min(reach, std::min(xw, W - xw));
    reach -= m.clearance_margin;
    const bool anchored = recorded && reach > 0;
    r.contact.clear_r2[i] = anchored ? reach * reach : -1.0;
    r.contact.clear_x[i] = x;
    r.contact.clear_y[i] = y;
    r.contact.clear_count[i] = anchored ? count : 0;
    if (anchored) std::copy(inside, inside + count, r.contact.clear_discs.begin() + static_cast<std::ptrdiff_t>(first));
  };
  int i = 0;
#if defined(SOFTDROP_AVX_DISPATCH)
  if (constraint_vector_width() >= VectorWidth::avx) {
    // Eight masses at a time: most are in their balls, free or inside their anchor's one disc. The
    // vector code reads plain arrays (contact_limit_wide.hpp), so each field is set here, once.
    lanes::ContactRecords records;
    records.x = r.state.x.data();
    records.y = r.state.y.data();
    records.clear_x = r.contact.clear_x.data();
    records.clear_y = r.contact.clear_y.data();
    records.clear_r2 = r.contact.clear_r2.data();
    records.clear_count = r.contact.clear_count.data();
    records.disc_x = r.contact.disc_x.data();
    records.disc_y = r.contact.disc_y.data();
    records.disc_r = r.contact.disc_r.data();
    records.contact_x = r.contact.x.data();
    records.contact_y = r.contact.y.data();
    records.contact_count = r.contact.count.data();
    records.disc_grain = r.contact.disc_grain.data();
    records.no_grain = no_grain;
    records.px = r.state.px.data();
    records.py = r.state.py.data();
    records.kc = m.params.kc;
    records.cc = m.params.cc;
    records.inv_dt = 1.0 / m.params.dt;
    records.force_x = r.contact.fx.data();
    records.force_y = r.contact.fy.data();
    records.touch = r.contact.touch.data();
    records.periodic = periodic;
    records.width = W;
    records.wrap_below = 0.999999 * W;
    constexpr int kChunk = 16;  // groups of eight per call
    unsigned todo[kChunk];
    while (i + 8 <= n) {
      const int groups = std::min(kChunk, (n - i) / 8);
      lanes::limit_groups(records, i / 8, groups, limit, deepest, todo);
      for (int g = 0; g < groups; ++g, i += 8)
        for (unsigned left = todo[g]; left != 0; left &= left - 1) limit_mass(i + std::countr_zero(left));
    }
  }
#endif
  for (; i < n; ++i) limit_mass(i);
  // The maximum does not depend on the order.
  r.contact.deepest = *std::max_element(deepest, deepest + 8);
  r.contact.current = true;
}

}  // namespace softdrop
