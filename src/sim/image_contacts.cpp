// The contact stages against an image medium's solid (image_contacts.hpp).
#include "image_contacts.hpp"

#include <algorithm>

#include "step_helpers.hpp"

namespace softdrop {

using step_detail::wrap_periodic;

void image_collisions(const DropletModel& m, DropletRuntime& r, double* fx, double* fy, std::ptrdiff_t stride) {
  const int n = r.state.size();
  const double kc = m.params.kc, cc = m.params.cc, inv_dt = 1.0 / m.params.dt;
  const double W = m.medium.width;
  const bool periodic = m.medium.periodic;
  const DistanceField& field = *m.field;
  double deepest = 0;
  r.contact.current = false;  // the contact limit leaves no record here
  for (int i = 0; i < n; ++i) {
    const double x = r.state.x[i], y = r.state.y[i];
    const double vx = (x - r.state.px[i]) * inv_dt, vy = (y - r.state.py[i]) * inv_dt;
    DistanceField::Sample s;
    if (field.sample(periodic ? wrap_periodic(x, W) : x, y, &s)) {
      const double depth = -s.d;
      const double f = std::max(0.0, kc * depth - cc * (vx * s.nx + vy * s.ny));
      fx[i * stride] += f * s.nx;
      fy[i * stride] += f * s.ny;
      r.touched[static_cast<std::size_t>(s.part)] = 1;
      deepest = std::max(deepest, depth);
    }
    if (!periodic) {  // solid side walls, as in a medium of grains
      if (x < 0) fx[i * stride] += std::max(0.0, -kc * x - cc * vx);
      if (x > W) fx[i * stride] -= std::max(0.0, kc * (x - W) + cc * vx);
    }
  }
  r.last_penetration = deepest;
}

void image_contact_limit(const DropletModel& m, DropletRuntime& r) {
  const int n = r.state.size();
  const double W = m.medium.width, limit = m.params.max_depth;
  const bool periodic = m.medium.periodic;
  const DistanceField& field = *m.field;
  r.contact.current = false;
  for (int i = 0; i < n; ++i) {
    DistanceField::Sample s;
    const double x = r.state.x[i], y = r.state.y[i];
    if (!field.sample(periodic ? wrap_periodic(x, W) : x, y, &s) || s.d >= -limit) continue;
    const double push = -limit - s.d;
    const double vx = x - r.state.px[i], vy = y - r.state.py[i];
    const double vn = std::min(0.0, vx * s.nx + vy * s.ny);  // inward displacement per step
    r.state.x[i] += push * s.nx;
    r.state.y[i] += push * s.ny;
    r.state.px[i] = r.state.x[i] - (vx - vn * s.nx);
    r.state.py[i] = r.state.y[i] - (vy - vn * s.ny);
    r.block.id = 0;  // the block's centre of mass is no longer the state's
  }
}

}  // namespace softdrop
