// A droplet's parameters (their checks and derived lengths), its placement, the constraint orders.
#include "softdrop/droplet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "util/enum_names.hpp"
#include "util/validation.hpp"

namespace softdrop {
using detail::fail;
using detail::num;
double DropletParams::rest_length() const { return 2 * radius * std::sin(M_PI / masses) / (1 + max_strain); }

namespace {
// Area of the regular n-gon of circumradius r.
double regular_polygon_area(int n, double r) { return 0.5 * n * r * r * std::sin(2 * M_PI / n); }
}  // namespace

double DropletParams::inflated_area() const { return regular_polygon_area(masses, radius); }

double DropletParams::resting_radius() const {
  // Each mass of the regular N-gon feels the gas's 2 nRT / (N rho) outward and its two springs'
  // 2 k_s (d - d0) sin(pi/N) inward, with d = 2 rho sin(pi/N): the positive root of
  // 2 k_s s^2 rho^2 - k_s s d0 rho - nRT / N = 0 (s = sin(pi/N)).
  if (!(ks > 0)) return radius;  // no springs: the gas inflates the ring to its limit
  const double s = std::sin(M_PI / masses), a = 2 * ks * s * s, b = ks * s * rest_length(), c = nrt / masses;
  const double rho = (b + std::sqrt(b * b + 4 * a * c)) / (2 * a);
  return std::min(rho, radius);  // (rho > d0 / (2 s): a gas always stretches the springs a little)
}

double DropletParams::resting_area() const { return regular_polygon_area(masses, resting_radius()); }

double DropletParams::viscous_rate() const {
  // -expm1(-x) = 1 - exp(-x) without the cancellation of small x.
  switch (viscosity_step) {
    case ViscosityStep::exponential:
      return -std::expm1(-viscosity * dt) / dt;
    case ViscosityStep::implicit:
      return viscosity / (1 + viscosity * dt);  // on the kicked velocity
    case ViscosityStep::explicit_euler:
      break;
  }
  return viscosity;
}

DropletParams DropletParams::balloon() {
  DropletParams p;
  p.nrt = 1.5e9;
  p.ks = 119755;
  p.kd = 365;
  p.cc = 2e4;
  p.dt = 2e-5;
  p.viscosity = 3e3;
  p.viscosity_dilation = 1;
  p.viscosity_step = ViscosityStep::explicit_euler;
  return p;
}

DropletParams DropletParams::explicit_step() {
  DropletParams p;
  p.viscosity_step = ViscosityStep::explicit_euler;
  p.viscosity = 1.37e5;
  p.dt = 3.5e-6;
  return p;
}

DropletParams DropletParams::exponential_step() {
  DropletParams p;
  p.viscosity_step = ViscosityStep::exponential;
  p.viscosity = 2.8e5;
  return p;
}

DropletParams DropletParams::passage() {
  DropletParams p;
  p.viscosity_step = ViscosityStep::exponential;
  p.radius = 5;
  p.nrt = 1.59e9;
  p.kc = 2.5e8;
  p.viscosity = 1e6;
  return p;
}

namespace {
// "must be > 0", "must be in (0, 0.01]", "must be finite": the range in words, its bounds printed
// as the field's type prints.
template <class T>
std::string range_words(const FieldRange& r) {
  auto bound = [](double b) {
    if constexpr (std::is_integral_v<T>)
      return std::to_string(static_cast<long long>(b));
    else
      return num(b);
  };
  const bool has_lo = std::isfinite(r.lo), has_hi = std::isfinite(r.hi);
  if (!has_lo && !has_hi) return "must be finite";
  if (!has_hi) return std::string("must be ") + (r.lo_included ? ">= " : "> ") + bound(r.lo);
  if (!has_lo) return std::string("must be ") + (r.hi_included ? "<= " : "< ") + bound(r.hi);
  return std::string("must be in ") + (r.lo_included ? "[" : "(") + bound(r.lo) + ", " + bound(r.hi) +
         (r.hi_included ? "]" : ")");
}

bool in_range(double v, const FieldRange& r) {
  return std::isfinite(v) && (r.lo_included ? v >= r.lo : v > r.lo) && (r.hi_included ? v <= r.hi : v < r.hi);
}
}  // namespace

bool DropletParams::IsValid(std::string* why) const {
  // Each field on its own, in the order of the field list; the first out of its range is named.
  std::string first;
  visit_droplet_fields(
      [&](const DropletField& field, const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_arithmetic_v<T>) {
          if (!first.empty() || in_range(static_cast<double>(v), field.range)) return;
          const std::string value = std::is_integral_v<T> ? std::to_string(v) : num(static_cast<double>(v));
          first = std::string(field.key) + " = " + value + ": " + range_words<T>(field.range);
        }
      },
      *this);
  if (!first.empty()) return fail(why, first);
  // The limits that join fields.
  // Names both nu and dt, since either may be the one the user changed.
  if (viscosity_step == ViscosityStep::explicit_euler && viscosity * dt > 0.5)
    return fail(why, "viscosity = " + num(viscosity) + ", dt = " + num(dt) +
                         ": viscosity * dt = " + num(viscosity * dt) + " must be <= 0.5 for viscosity-step explicit");
  // Explicit integration is only stable when the stiffest oscillator is resolved in time.
  const double omega_dt = std::sqrt(std::max(ks, kc) / mass) * dt;
  if (omega_dt > 0.5)
    return fail(why, "dt = " + num(dt) + ": too large for the stiffness, sqrt(max(ks, kc) / mass) * dt = " +
                         num(omega_dt) + " must be <= 0.5");
  if (std::max(kd, cc) * dt / mass > 1.0)
    return fail(why, "dt = " + num(dt) + ": too large for the damping, max(kd, cc) * dt / mass = " +
                         num(std::max(kd, cc) * dt / mass) + " must be <= 1");
  // The ring's fastest mode, neighbours moving against each other, sees the springs as
  // a = 4 k_s dt^2 / m a step and the spring damping and the viscosity together as
  // b = (4 k_d / m + viscous rate) dt (the viscosity damps it whole: it is pure deformation).
  // Position Verlet with the backward velocity keeps it bounded only while a + 2 b < 4 (b < 2
  // follows); the checks above alone let a + 2 b reach 10.
  const double a = 4 * ks * dt * dt / mass, b = (4 * kd / mass + viscous_rate()) * dt;
  if (a + 2 * b >= 4)
    return fail(why, "dt = " + num(dt) +
                         ": too large for the ring's fastest mode, 4 ks dt^2 / mass + 2 (4 kd / mass + " +
                         "nu_rate) dt = " + num(a + 2 * b) + " must be < 4 (nu_rate = " + num(viscous_rate()) +
                         ", the viscosity as the step applies it)");
  if (vibrates() && !(vibration_frequency > 0))
    return fail(why, "vibration-frequency = " + num(vibration_frequency) +
                         ": must be > 0 when vibration-amplitude = " + num(vibration_amplitude) + " shakes the medium");
  // The cosine is sampled once a step; fewer than 20 samples a period would shake with another
  // waveform than the one asked for.
  if (vibrates() && vibration_frequency * dt > 0.05)
    return fail(why, "vibration-frequency = " + num(vibration_frequency) + ", dt = " + num(dt) + ": a period of " +
                         num(1 / (vibration_frequency * dt)) + " steps; it must span at least 20");
  return true;
}

namespace {
// v on each axis the medium shakes along, 0 on the other.
void along_axis(VibrationAxis axis, double v, double* x, double* y) {
  *x = axis == VibrationAxis::y ? 0.0 : v;
  *y = axis == VibrationAxis::x ? 0.0 : v;
}
}  // namespace

void DropletParams::vibration_acceleration(double t, double* ax, double* ay) const {
  // The grains' acceleration is A w^2 cos(w t); in their frame each mass feels its opposite.
  const double w = 2 * M_PI * vibration_frequency;
  along_axis(vibration_axis, -vibration_amplitude * w * w * std::cos(w * t), ax, ay);
}

void DropletParams::vibration_displacement(double t, double* dx, double* dy) const {
  along_axis(vibration_axis, vibration_amplitude * (1 - std::cos(2 * M_PI * vibration_frequency * t)), dx, dy);
}

void DropletState::resize(int n) {
  for (auto* v : {&x, &y, &px, &py, &fx, &fy}) v->assign(static_cast<std::size_t>(n), 0.0);
}

void place_droplet(const DropletParams& params, double cx, double cy, DropletState* state) {
  state->resize(params.masses);
  const double rho = params.resting_radius();
  for (int i = 0; i < params.masses; ++i) {
    const double a = 2 * M_PI * i / params.masses;
    state->x[i] = state->px[i] = cx + rho * std::cos(a);
    state->y[i] = state->py[i] = cy + rho * std::sin(a);
  }
}

constexpr detail::EnumName<ConstraintOrder> kConstraintOrders[] = {{ConstraintOrder::sequential, "sequential"},
                                                                   {ConstraintOrder::red_black, "red-black"}};

ConstraintOrder parse_constraint_order(const std::string& name) {
  return detail::parse_name(kConstraintOrders, name, "constraint-order");
}

const char* to_string(ConstraintOrder order) { return detail::name_of(kConstraintOrders, order); }

std::vector<std::string> constraint_order_names() { return detail::name_list(kConstraintOrders); }

constexpr detail::EnumName<ViscosityStep> kViscositySteps[] = {{ViscosityStep::explicit_euler, "explicit"},
                                                               {ViscosityStep::exponential, "exponential"},
                                                               {ViscosityStep::implicit, "implicit"}};

ViscosityStep parse_viscosity_step(const std::string& name) {
  return detail::parse_name(kViscositySteps, name, "viscosity-step");
}

const char* to_string(ViscosityStep step) { return detail::name_of(kViscositySteps, step); }

void parse_name(const std::string& name, ConstraintOrder* value) { *value = parse_constraint_order(name); }
void parse_name(const std::string& name, ViscosityStep* value) { *value = parse_viscosity_step(name); }
std::vector<std::string> value_names(ConstraintOrder) { return constraint_order_names(); }
std::vector<std::string> value_names(ViscosityStep) { return detail::name_list(kViscositySteps); }

constexpr detail::EnumName<VibrationAxis> kVibrationAxes[] = {
    {VibrationAxis::x, "x"}, {VibrationAxis::y, "y"}, {VibrationAxis::xy, "xy"}};
constexpr detail::EnumName<VibrationStart> kVibrationStarts[] = {{VibrationStart::rest, "rest"},
                                                                 {VibrationStart::start, "start"}};
const char* to_string(VibrationAxis axis) { return detail::name_of(kVibrationAxes, axis); }
const char* to_string(VibrationStart start) { return detail::name_of(kVibrationStarts, start); }
void parse_name(const std::string& name, VibrationAxis* value) {
  *value = detail::parse_name(kVibrationAxes, name, "vibration-axis");
}
void parse_name(const std::string& name, VibrationStart* value) {
  *value = detail::parse_name(kVibrationStarts, name, "vibration-start");
}
std::vector<std::string> value_names(VibrationAxis) { return detail::name_list(kVibrationAxes); }
std::vector<std::string> value_names(VibrationStart) { return detail::name_list(kVibrationStarts); }

}  // namespace softdrop
