// Contacts between two droplets' rings (ring_contact.hpp): the edge grid, the nearest edge of the
// other ring to a mass, and the two stages.
#include "ring_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "step_test_seam.hpp"

namespace softdrop {

namespace {

// The smallest power of two >= n.
std::uint64_t power_of_two_at_least(std::uint64_t n) {
  std::uint64_t p = 1;
  while (p < n) p <<= 1;
  return p;
}

// Where a mass meets the other ring: its nearest edge, the place t in [0, 1] along it, the signed
// distance d (< 0: inside the ring), and n, the unit direction out of the ring at that place.
struct EdgeHit {
  int edge = -1;
  double t = 0, d = 0, nx = 0, ny = 0;
};

// The outward normal of edge j of a counter-clockwise ring, not normalised: (e_y, -e_x).
void outward(const DropletState& s, int j, double* nx, double* ny) {
  const int k = j + 1 == s.size() ? 0 : j + 1;
  *nx = s.y[k] - s.y[j];
  *ny = -(s.x[k] - s.x[j]);
}

// The nearest edge of ring e (listed in grid) to (x, y), if one is within reach.
bool nearest_edge(const DropletState& e, const EdgeGrid& grid, double x, double y, double reach, EdgeHit* hit) {
  const std::int32_t *j = nullptr, *end = nullptr;
  grid.cell(x, y, &j, &end);
  const int n = e.size();
  const double s = grid.shift();
  double best = reach * reach;
  int found = -1;
  double ft = 0, fqx = 0, fqy = 0;
  for (; j != end; ++j) {
    const int a = *j, b = a + 1 == n ? 0 : a + 1;
    const double ax = e.x[a] + s, ay = e.y[a], ex = e.x[b] + s - ax, ey = e.y[b] - ay;
    const double len2 = ex * ex + ey * ey;
    const double t = len2 > 0 ? std::clamp(((x - ax) * ex + (y - ay) * ey) / len2, 0.0, 1.0) : 0.0;
    const double qx = ax + t * ex, qy = ay + t * ey;
    const double d2 = (x - qx) * (x - qx) + (y - qy) * (y - qy);
    if (d2 < best || (found < 0 && d2 == best)) {  // the first of equals: the lists ascend
      best = d2;
      found = a;
      ft = t, fqx = qx, fqy = qy;
    }
  }
  if (found < 0) return false;
  // Inside or out: the side of the edge, or at a corner the side of the corner's pseudo-normal
  // (the sum of its two edges' unit normals), which decides rightly for any closed polyline.
  double nx, ny;
  outward(e, found, &nx, &ny);
  const double len_n = std::hypot(nx, ny);
  double sx = nx / len_n, sy = ny / len_n;
  if (ft == 0 || ft == 1) {
    const int other = ft == 0 ? (found == 0 ? n - 1 : found - 1) : (found + 1 == n ? 0 : found + 1);
    double ox, oy;
    outward(e, other, &ox, &oy);
    const double len_o = std::hypot(ox, oy);
    sx += ox / len_o;
    sy += oy / len_o;
  }
  const bool inside = (x - fqx) * sx + (y - fqy) * sy < 0;
  const double dist = std::sqrt(best);
  hit->edge = found;
  hit->t = ft;
  hit->d = inside ? -dist : dist;
  if (dist > 0) {
    const double sign = inside ? -1.0 : 1.0;
    hit->nx = sign * (x - fqx) / dist;
    hit->ny = sign * (y - fqy) / dist;
  } else if (const double len = std::hypot(sx, sy); len > 0) {
    hit->nx = sx / len;
    hit->ny = sy / len;
  } else {  // on a corner whose edges fold back onto each other: the edge's own normal
    hit->nx = nx / len_n;
    hit->ny = ny / len_n;
  }
  return true;
}

// The reach of the grids: twice the contact's, so that a mass that went a little inside the other
// ring within a step still finds the edge it crossed.
double grid_reach(const DropletModel& m) { return 2 * m.params.max_depth; }

// How near the other ring's box a mass must be to query its grid: the reach, and half of it again.
// A mass further out is further than the reach from every edge by a margin many orders of magnitude
// beyond the rounding of a coordinate, so it could not have found one: leaving it out changes no bit.
double query_margin(const DropletModel& m) {
#if defined(SOFTDROP_TEST_HOOKS)
  if (!test_seam::ring_pruning().load(std::memory_order_relaxed)) return std::numeric_limits<double>::infinity();
#endif
  return 1.5 * grid_reach(m);
}

// Ring s's bounding box.
RingBox box_of(const DropletState& s) {
  RingBox b = RingBox::at(s.x[0], s.y[0]);
  for (int i = 1; i < s.size(); ++i) b.add(s.x[i], s.y[i]);
  return b;
}

// Box b, its x shifted by `shift` (into the frame of the other ring).
RingBox shifted(RingBox b, double shift) {
  b.x0 += shift;
  b.x1 += shift;
  return b;
}

// Whether boxes a and b come within reach of each other.
bool boxes_meet(const RingBox& a, const RingBox& b, double reach) {
  return !(b.x0 > a.x1 + reach || a.x0 > b.x1 + reach || b.y0 > a.y1 + reach || a.y0 > b.y1 + reach);
}

// Whether ring b, its x shifted by s, may come within reach of ring a, judged on one mass of each:
// every mass of a ring is within half its perimeter, N (1 + max_strain) d0 / 2, of every other.
bool first_masses_near(const DropletModel& m, const DropletState& a, const DropletState& b, double s, double reach) {
  const double far = a.size() * (1 + m.params.max_strain) * m.context.rest_length + reach;
  return !(std::abs(b.x[0] + s - a.x[0]) > far || std::abs(b.y[0] - a.y[0]) > far);
}

// The penalty between the masses of ring p and the edges of ring e, whose box in p's frame is
// `box`, added to their forces fp and fe. The grid lists e's edges near the masses that can touch
// them; none is built when no mass can.
std::int64_t penalty(const DropletModel& m, const DropletRuntime& p, const DropletRuntime& e, const RingBox& box,
                     double shift, EdgeGrid* grid, RingForces fp, RingForces fe) {
  const double margin = query_margin(m);
  const DropletState& ps = p.state;
  // The masses of p near e's box, and their box widened by the margin beyond the reach.
  bool any = false;
  RingBox near_masses;
  for (int i = 0; i < ps.size(); ++i) {
    if (!box.near(ps.x[i], ps.y[i], margin)) continue;
    if (any) {
      near_masses.add(ps.x[i], ps.y[i]);
    } else {
      near_masses = RingBox::at(ps.x[i], ps.y[i]);
      any = true;
    }
  }
  if (!any) return 0;
  const double slack = margin - grid_reach(m);
  const RingBox only{near_masses.x0 - slack, near_masses.x1 + slack, near_masses.y0 - slack, near_masses.y1 + slack};
  grid->build(e.state, shift, grid_reach(m), std::isfinite(slack) ? &only : nullptr);
  const double skin = m.params.max_depth, kc = m.params.kc, cc = m.params.cc, inv_dt = m.context.inv_dt;
  const DropletState& es = e.state;
  const int ne = es.size();
  std::int64_t contacts = 0;
  for (int i = 0; i < ps.size(); ++i) {
    if (!box.near(ps.x[i], ps.y[i], margin)) continue;
    EdgeHit h;
    if (!nearest_edge(es, *grid, ps.x[i], ps.y[i], grid_reach(m), &h)) continue;
    if (!(h.d < skin)) continue;
    const int a = h.edge, b = a + 1 == ne ? 0 : a + 1;
    const double t = h.t;
    // The mass's velocity relative to the edge's point (position Verlet's backward velocities).
    const double vx = (ps.x[i] - ps.px[i]) - (1 - t) * (es.x[a] - es.px[a]) - t * (es.x[b] - es.px[b]);
    const double vy = (ps.y[i] - ps.py[i]) - (1 - t) * (es.y[a] - es.py[a]) - t * (es.y[b] - es.py[b]);
    const double f = std::max(0.0, kc * (skin - h.d) - cc * (vx * h.nx + vy * h.ny) * inv_dt);
    ++contacts;
    if (f == 0) continue;
    const double fx = f * h.nx, fy = f * h.ny;
    fp.fx[i * fp.stride] += fx;
    fp.fy[i * fp.stride] += fy;
    fe.fx[a * fe.stride] -= (1 - t) * fx;
    fe.fy[a * fe.stride] -= (1 - t) * fy;
    fe.fx[b * fe.stride] -= t * fx;
    fe.fy[b * fe.stride] -= t * fy;
  }
  return contacts;
}

// The limit between the masses of ring p and the edges of ring e, whose box in p's frame is `box`.
// The grid lists all of e's edges, built at the first mass near the box, before anything moved.
int limit(const DropletModel& m, DropletRuntime& p, DropletRuntime& e, RingBox box, double shift, EdgeGrid* grid) {
  const double margin = query_margin(m);
  bool built = false;
  // A mass inside is moved out to a thousandth of max_depth outside the other ring, so that the
  // rounding of the correction leaves it outside.
  const double clear = 1e-3 * m.params.max_depth;
  DropletState& es = e.state;
  DropletState& ps = p.state;
  const int ne = es.size();
  int moved = 0;
  for (int i = 0; i < ps.size(); ++i) {
    if (!box.near(ps.x[i], ps.y[i], margin)) continue;
    if (!built) grid->build(es, shift, grid_reach(m));
    built = true;
    EdgeHit h;
    if (!nearest_edge(es, *grid, ps.x[i], ps.y[i], grid_reach(m), &h) || !(h.d < 0)) continue;
    const int a = h.edge, b = a + 1 == ne ? 0 : a + 1;
    const double t = h.t, u = 1 - t;
    // The mass moves by s n and the edge's ends by -s (1 - t) n and -s t n: the displacements sum
    // to zero, and the edge's point moves by -s ((1 - t)^2 + t^2) n.
    const double w = 1 + u * u + t * t;
    const double s = (clear - h.d) / w;
    const double dx = s * h.nx, dy = s * h.ny;
    ps.x[i] += dx, ps.px[i] += dx, ps.y[i] += dy, ps.py[i] += dy;
    es.x[a] -= u * dx, es.px[a] -= u * dx, es.y[a] -= u * dy, es.py[a] -= u * dy;
    es.x[b] -= t * dx, es.px[b] -= t * dx, es.y[b] -= t * dy, es.py[b] -= t * dy;
    // The approach stops: an impulse along n, shared in the same proportions, takes the relative
    // normal velocity to zero (a displacement per step, (x - px)).
    const double vx = (ps.x[i] - ps.px[i]) - u * (es.x[a] - es.px[a]) - t * (es.x[b] - es.px[b]);
    const double vy = (ps.y[i] - ps.py[i]) - u * (es.y[a] - es.py[a]) - t * (es.y[b] - es.py[b]);
    const double vn = vx * h.nx + vy * h.ny;
    if (vn < 0) {
      const double j = -vn / w, jx = j * h.nx, jy = j * h.ny;
      ps.px[i] -= jx, ps.py[i] -= jy;
      es.px[a] += u * jx, es.py[a] += u * jy;
      es.px[b] += t * jx, es.py[b] += t * jy;
    }
    // The box keeps holding every mass of e, so it still tells which later masses can reach it.
    box.add(es.x[a] + shift, es.y[a]);
    box.add(es.x[b] + shift, es.y[b]);
    ++moved;
  }
  return moved;
}

}  // namespace

std::uint64_t EdgeGrid::bucket(std::int64_t ix, std::int64_t iy) const {
  const auto ux = static_cast<std::uint64_t>(ix), uy = static_cast<std::uint64_t>(iy);
  return ((ux * 0x9E3779B97F4A7C15ULL) ^ (uy * 0xC2B2AE3D27D4EB4FULL)) >> 20 & mask_;
}

void EdgeGrid::build(const DropletState& ring, double shift_x, double reach, const RingBox* only) {
  const int n = ring.size();
  shift_ = shift_x;
  mask_ = power_of_two_at_least(2 * static_cast<std::uint64_t>(n)) - 1;
  // The edges to list: all, or those whose box widened by the reach meets `only`.
  const auto listed = [&](int j, int k) {
    if (!only) return true;
    const double xa = ring.x[j] + shift_x, xb = ring.x[k] + shift_x;
    return !(std::min(xa, xb) - reach > only->x1 || std::max(xa, xb) + reach < only->x0 ||
             std::min(ring.y[j], ring.y[k]) - reach > only->y1 || std::max(ring.y[j], ring.y[k]) + reach < only->y0);
  };
  // A cell as wide as the longest listed edge's box widened by the reach on both sides: each edge
  // is listed in at most four cells.
  double longest = 0;
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    if (listed(j, k)) longest = std::max({longest, std::abs(ring.x[k] - ring.x[j]), std::abs(ring.y[k] - ring.y[j])});
  }
  cell_ = longest + 2 * reach;
  start_.assign(mask_ + 2, 0);
  cells_.clear();
  listed_.clear();
  // Each edge's cells, as (bucket, edge) in edge order; then a counting sort by bucket, stable.
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    if (!listed(j, k)) continue;
    const double xa = ring.x[j] + shift_x, xb = ring.x[k] + shift_x;
    const auto ix0 = static_cast<std::int64_t>(std::floor((std::min(xa, xb) - reach) / cell_));
    const auto ix1 = static_cast<std::int64_t>(std::floor((std::max(xa, xb) + reach) / cell_));
    const auto iy0 = static_cast<std::int64_t>(std::floor((std::min(ring.y[j], ring.y[k]) - reach) / cell_));
    const auto iy1 = static_cast<std::int64_t>(std::floor((std::max(ring.y[j], ring.y[k]) + reach) / cell_));
#if defined(SOFTDROP_TEST_HOOKS)
    ++test_seam::ring_grid_edges();
#endif
    for (std::int64_t ix = ix0; ix <= ix1; ++ix)
      for (std::int64_t iy = iy0; iy <= iy1; ++iy) {
        const std::uint64_t key = bucket(ix, iy);
        cells_.push_back(key);
        listed_.push_back(j);
        ++start_[key + 1];
      }
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  entries_.resize(listed_.size());
  next_.assign(start_.begin(), start_.end() - 1);
  for (std::size_t e = 0; e < listed_.size(); ++e) entries_[static_cast<std::size_t>(next_[cells_[e]]++)] = listed_[e];
}

void EdgeGrid::cell(double x, double y, const std::int32_t** begin, const std::int32_t** end) const {
  const std::uint64_t key =
      bucket(static_cast<std::int64_t>(std::floor(x / cell_)), static_cast<std::int64_t>(std::floor(y / cell_)));
  *begin = entries_.data() + start_[key];
  *end = entries_.data() + start_[key + 1];
}

double periodic_shift(const DropletState& a, const DropletState& b, const Medium& medium) {
  if (!medium.periodic) return 0;
  const double W = medium.width;
  return -W * std::round((b.x[0] - a.x[0]) / W);
}

void ring_contacts_stage(const DropletModel& m, const DropletRuntime& a, const DropletRuntime& b,
                         RingContactScratch* scratch, RingForces fa, RingForces fb) {
  scratch->contacts = 0;
  const double s = periodic_shift(a.state, b.state, m.medium), reach = grid_reach(m);
  // Rings further apart than the reach: no contact, and no grid to build.
  if (!first_masses_near(m, a.state, b.state, s, reach)) return;
  const RingBox box_a = box_of(a.state), box_b = shifted(box_of(b.state), s);  // in a's frame
  if (!boxes_meet(box_a, box_b, reach)) return;
  scratch->contacts += penalty(m, a, b, box_b, s, &scratch->edges[1], fa, fb);
  scratch->contacts += penalty(m, b, a, shifted(box_a, -s), -s, &scratch->edges[0], fb, fa);  // in b's frame
}

int ring_limit_stage(const DropletModel& m, DropletRuntime& a, DropletRuntime& b, RingContactScratch* scratch) {
  const double s = periodic_shift(a.state, b.state, m.medium), reach = grid_reach(m);
  if (!first_masses_near(m, a.state, b.state, s, reach)) return 0;
  const RingBox box_a = box_of(a.state), box_b = shifted(box_of(b.state), s);
  if (!boxes_meet(box_a, box_b, reach)) return 0;
  const int moved_a = limit(m, a, b, box_b, s, &scratch->edges[1]);
  // In b's frame, with a's box as a's moves left it.
  const int moved_b = limit(m, b, a, shifted(moved_a > 0 ? box_of(a.state) : box_a, -s), -s, &scratch->edges[0]);
  if (moved_a + moved_b > 0) {
    // Both rings may have moved (a mass, or an edge's ends).
    a.changed();
    b.changed();
  }
  return moved_a + moved_b;
}

bool rings_within(const DropletState& a, const DropletState& b, const Medium& medium, double reach) {
  return boxes_meet(box_of(a), shifted(box_of(b), periodic_shift(a, b, medium)), reach);
}

}  // namespace softdrop
