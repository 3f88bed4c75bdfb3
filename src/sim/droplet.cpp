// A droplet's parameters (their checks and derived lengths), its placement, the constraint orders.
#include "softdrop/droplet.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "util/validation.hpp"

namespace softdrop {
using detail::fail;
using detail::num;
namespace {
bool positive(double v) { return std::isfinite(v) && v > 0; }
}  // namespace

double DropletParams::rest_length() const {
  return 2 * radius * std::sin(M_PI / masses) / (1 + max_strain);
}

double DropletParams::inflated_area() const {
  return 0.5 * masses * radius * radius * std::sin(2 * M_PI / masses);
}

bool DropletParams::IsValid(std::string* why) const {
  if (masses < 8 || masses > 100000)
    return fail(why, "masses = " + std::to_string(masses) + ": must be in [8, 100000]");
  if (!positive(mass)) return fail(why, "mass = " + num(mass) + ": must be > 0");
  if (!positive(radius)) return fail(why, "radius = " + num(radius) + ": must be > 0");
  if (!positive(nrt)) return fail(why, "nrt = " + num(nrt) + ": must be > 0");
  if (!std::isfinite(ks) || ks < 0) return fail(why, "ks = " + num(ks) + ": must be >= 0");
  if (!std::isfinite(kd) || kd < 0) return fail(why, "kd = " + num(kd) + ": must be >= 0");
  if (!positive(kc)) return fail(why, "kc = " + num(kc) + ": must be > 0");
  if (!std::isfinite(cc) || cc < 0) return fail(why, "cc = " + num(cc) + ": must be >= 0");
  if (!std::isfinite(gravity)) return fail(why, "gravity = " + num(gravity) + ": must be finite");
  if (!positive(dt) || dt > 1e-2) return fail(why, "dt = " + num(dt) + ": must be in (0, 0.01]");
  if (!std::isfinite(max_strain) || max_strain <= 0 || max_strain >= 0.5)
    return fail(why, "max-strain = " + num(max_strain) + ": must be in (0, 0.5)");
  if (constraint_iterations < 0 || constraint_iterations > 100)
    return fail(why, "constraint-iterations = " + std::to_string(constraint_iterations) +
                         ": must be in [0, 100]");
  if (!std::isfinite(max_depth) || max_depth <= 0)
    return fail(why, "max-depth = " + num(max_depth) + ": must be > 0");
  if (!std::isfinite(viscosity) || viscosity < 0)
    return fail(why, "viscosity = " + num(viscosity) + ": must be >= 0");
  if (viscosity * dt > 0.5)  // names both, since either may be the one the user changed
    return fail(why, "viscosity = " + num(viscosity) + ", dt = " + num(dt) + ": viscosity * dt = " +
                         num(viscosity * dt) + " must be <= 0.5");
  // Explicit integration is only stable when the stiffest oscillator is resolved in time.
  const double omega_dt = std::sqrt(std::max(ks, kc) / mass) * dt;
  if (omega_dt > 0.5)
    return fail(why, "dt = " + num(dt) + ": too large for the stiffness, sqrt(max(ks, kc) / mass) * dt = " +
                         num(omega_dt) + " must be <= 0.5");
  if (std::max(kd, cc) * dt / mass > 1.0)
    return fail(why, "dt = " + num(dt) + ": too large for the damping, max(kd, cc) * dt / mass = " +
                         num(std::max(kd, cc) * dt / mass) + " must be <= 1");
  return true;
}

void DropletState::resize(int n) {
  for (auto* v : {&x, &y, &px, &py, &fx, &fy}) v->assign(static_cast<std::size_t>(n), 0.0);
}

void place_droplet(const DropletParams& params, double cx, double cy, DropletState* state) {
  state->resize(params.masses);
  for (int i = 0; i < params.masses; ++i) {
    const double a = 2 * M_PI * i / params.masses;
    state->x[i] = state->px[i] = cx + params.radius * std::cos(a);
    state->y[i] = state->py[i] = cy + params.radius * std::sin(a);
  }
}

ConstraintOrder parse_constraint_order(const std::string& name) {
  if (name == "sequential") return ConstraintOrder::sequential;
  if (name == "red-black") return ConstraintOrder::red_black;
  throw std::invalid_argument("constraint-order '" + name + "': expected sequential or red-black");
}

const char* to_string(ConstraintOrder order) {
  return order == ConstraintOrder::sequential ? "sequential" : "red-black";
}

}  // namespace softdrop
