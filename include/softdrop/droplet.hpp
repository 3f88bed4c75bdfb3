#pragma once
/// \file droplet.hpp
/// The soft-body droplet: parameters (what the user sets), creation data (topology and rest state
/// derived once) and runtime state (flat arrays advanced by the simulation).

#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace softdrop {

/// Physical and numerical parameters of a droplet. Units are the paper's pixel-like numerical
/// units: length in grid units, time in simulation time units, mass in mass units.
/// How the springs of one constraint pass are ordered.
enum class ConstraintOrder { sequential, red_black };
/// Parses "sequential" / "red-black"; throws std::invalid_argument naming the value.
ConstraintOrder parse_constraint_order(const std::string& name);
/// Every constraint order's name, in the enum's order.
std::vector<std::string> constraint_order_names();
const char* to_string(ConstraintOrder order);

/// How the internal viscosity advances a step.
/// - explicit: the force -m nu u on each mass's deformation velocity u, integrated as every other
///   force; u falls by (1 - nu dt) a step, which bounds nu dt <= 0.5 (the reference).
/// - exponential: the same force with m nu replaced by m (1 - exp(-nu dt)) / dt, so u falls by
///   exp(-nu dt) a step, the exact decay of du/dt = -nu u: any nu dt is stable, and dt is bounded
///   by the springs, the contacts and the ring's fastest mode (IsValid). The two agree to first
///   order in nu dt.
/// - implicit: backward Euler on the deformation velocity after the step's other forces: u' =
///   (u + a dt) / (1 + nu dt), a the deformation part of every other force a mass feels. Any nu dt
///   is stable, and a steadily pushed ring deforms at a / nu, the continuous rate, at every dt
///   (the exponential step's rate is a / nu times nu dt / (1 - exp(-nu dt)): its effective
///   viscosity grows as dt falls, and with it T).
enum class ViscosityStep { explicit_euler, exponential, implicit };
/// Parses "explicit" / "exponential" / "implicit"; throws std::invalid_argument naming the value.
ViscosityStep parse_viscosity_step(const std::string& name);
const char* to_string(ViscosityStep step);

/// The direction in which the medium is shaken: along x, along y, or along both at once, in phase
/// (the diagonal, with the amplitude on each axis).
enum class VibrationAxis { x, y, xy };
/// When the shaking begins: when the run first finds the droplet at rest (the rest test of
/// RunOptions), or with the run.
enum class VibrationStart { rest, start };
const char* to_string(VibrationAxis axis);
const char* to_string(VibrationStart start);

/// The enum fields of DropletParams by their names, alike for every enum: the command line, the
/// stored parameters and the Python properties parse and list them through these.
void parse_name(const std::string& name, ConstraintOrder* value);
void parse_name(const std::string& name, ViscosityStep* value);
void parse_name(const std::string& name, VibrationAxis* value);
void parse_name(const std::string& name, VibrationStart* value);
std::vector<std::string> value_names(ConstraintOrder);
std::vector<std::string> value_names(ViscosityStep);
std::vector<std::string> value_names(VibrationAxis);
std::vector<std::string> value_names(VibrationStart);

/// The defaults are a droplet whose springs carry the tension, calibrated against the paper's mean
/// tortuosity and area (results/calibration/README.md says how and how close; docs/model.md why
/// each value). It is a droplet of the paper's g, k_s and k_d (with N = 24, m = 1) at 8 400 times
/// our lengths, written in our lengths: the model is similar under x -> x / S, t -> t / sqrt(S)
/// with g fixed, which multiplies k_s by S, k_d, nu and 1 / dt by sqrt(S), and divides nRT by S.
/// Its internal viscosity nu = 1.37e5 takes the implicit step at dt = 6e-6 (the time-step study
/// of results/calibration/README.md). explicit_step() is the same droplet with the explicit step at
/// the dt that step needs; exponential_step() is the exponential step's calibration;
/// results/calibration/balloon.toml holds the balloon (held at its stretch limit).
struct DropletParams {
  int masses = 24;                ///< N, point masses on the ring
  double mass = 1.0;              ///< m, mass of each point
  double radius = 8.0;            ///< R, radius of the inflated droplet (ring at the stretch limit)
  double nrt = 2.29e9;            ///< nRT of the ideal gas, P = nRT / V (force x length); 5 % strain at rest
  double ks = 1.005942e9;         ///< spring stiffness k_s (force / length); the paper's 119 755 x 8 400
  double kd = 33452.8;            ///< spring damping k_d (force x time / length); the paper's 365 x sqrt(8 400)
  double kc = 2.0e8;              ///< collision penalty stiffness k_c (force / length)
  double cc = 0.0;                ///< collision normal damping (force x time / length)
  double gravity = -5.0e5;        ///< g_y, acceleration along y (length / time^2); g_x = 0; the paper's
  double dt = 6e-6;               ///< time step (time); the ring's fastest mode bounds it (IsValid)
  double max_strain = 0.1;        ///< Provot limit: |d - d0| / d0 <= max_strain after each step
  int constraint_iterations = 4;  ///< Gauss-Seidel passes of the Provot constraint per step
  /// Order of the springs within a pass. Sequential (ring order) is the reference; red-black does
  /// the even springs, then the odd ones: the springs of a half-pass share no mass, so they run
  /// independently (faster steps for one droplet: bench/README.md), with different rounding and
  /// so different numbers.
  ConstraintOrder constraint_order = ConstraintOrder::sequential;
  /// Contact inverse dynamics: a mass deeper than this inside a grain is moved back to this depth
  /// and loses its inward normal velocity (length; as a fraction of the smallest grain radius it
  /// bounds how far a grain can cut into the ring).
  double max_depth = 0.5;
  /// Internal viscosity nu (1/time): each mass feels -m nu (v_i - v_rigid,i), where v_rigid is the
  /// ring's rigid motion (centre-of-mass translation plus rotation). It dissipates deformation
  /// only, so the centre of mass still moves under gravity and contacts alone. 0 disables it.
  double viscosity = 1.37e5;
  /// The share of nu that acts on the ring's uniform dilation (its breathing mode, velocities
  /// delta (x_i - centre)): 1 damps it as any other deformation; 0 spares it, so a squeezed ring can
  /// overshoot and swell past its rest area. Like nu, it adds no net force or torque.
  double viscosity_dilation = 0.0;
  /// How nu advances a step (see ViscosityStep). Explicit is the reference, and what stored
  /// parameters without this key ran; implicit lets the defaults take a 1.7 times larger dt with
  /// the reference's continuous nu and <T>(phi).
  ViscosityStep viscosity_step = ViscosityStep::implicit;
  /// The medium shaken as a rigid body: its grains move by A (1 - cos 2 pi f t) along the axis, t
  /// the time since the shaking began, which starts them from rest, without a jolt. The droplet is
  /// stepped in the medium's frame, where that motion is each mass's inertial force
  /// -m A (2 pi f)^2 cos(2 pi f t) along the axis (the vibration stage): contacts, the spring
  /// damping and the viscosity see velocities relative to the grains, as they would, and the path,
  /// T included, is the centre's in the medium's frame. A = 0 (the default): no shaking, and the
  /// stage does not run. (length)
  double vibration_amplitude = 0.0;
  double vibration_frequency = 0.0;  ///< f (1/time); a period must span at least 20 steps
  VibrationAxis vibration_axis = VibrationAxis::x;
  /// When the shaking begins. From rest, the run's first rest or stuck verdict starts it instead of
  /// ending the run,
  /// and the stuck test alone (no net descent of stuck_distance within stuck_window) then ends a
  /// droplet that shaking does not free.
  VibrationStart vibration_start = VibrationStart::rest;

  /// Whether the medium is shaken (vibration_amplitude > 0).
  bool vibrates() const { return vibration_amplitude > 0; }
  /// The inertial acceleration the shaking gives each mass in the medium's frame, t time units
  /// after it began: -A (2 pi f)^2 cos(2 pi f t) on each axis it shakes (length / time^2).
  void vibration_acceleration(double t, double* ax, double* ay) const;
  /// How far the shaking has moved the medium t time units after it began: A (1 - cos 2 pi f t) on
  /// each axis it shakes (length).
  void vibration_displacement(double t, double* dx, double* dy) const;

  /// Rest length of a spring: d0 = 2 R sin(pi/N) / (1 + max_strain), so the ring at its stretch
  /// limit is the regular N-gon inscribed in the circle of radius R.
  double rest_length() const;
  /// Area of the inflated droplet, the regular N-gon of circumradius R.
  double inflated_area() const;
  /// Circumradius of the ring at rest in free fall: the regular N-gon on which the springs'
  /// tension balances the gas, k_s sin(pi/N) (2 rho sin(pi/N) - d0) rho = nRT / N, or R itself
  /// when the gas would stretch the springs past their limit (a balloon). A weak gas leaves the
  /// springs near their rest length d0. (length)
  double resting_radius() const;
  /// Area of the ring at rest, the regular N-gon of circumradius resting_radius(): S0 of the
  /// area ratios a run reports.
  double resting_area() const;
  /// The viscous coefficient a step applies per unit mass (1/time): nu for the explicit step,
  /// (1 - exp(-nu dt)) / dt for the exponential one (the force on a mass is -m rate u), and
  /// nu / (1 + nu dt) for the implicit one (on the velocity the other forces have kicked).
  double viscous_rate() const;
  /// The balloon: the paper's k_s, k_d and dt at R = 8, nRT = 1.5e9 holding every spring at the
  /// stretch limit, c_c = 2e4, nu = 3 000 (explicit step) damping every deformation
  /// (results/calibration/balloon.toml, which also sets its grains, radii 8 to 16).
  static DropletParams balloon();
  /// The defaults' droplet with the explicit viscosity step (the reference) at the dt it needs:
  /// dt = 3.5e-6 with the defaults' nu (results/calibration/explicit.toml).
  static DropletParams explicit_step();
  /// The droplet calibrated for the exponential viscosity step: nu = 2.8e5 at dt = 6e-6
  /// (results/calibration/exponential.toml). It is not converged in dt.
  static DropletParams exponential_step();
  /// A smaller droplet with a stiffer ring, for more passage at low porosity: R = 5, nRT = 1.59e9,
  /// k_c = 2.5e8, nu = 1e6, for grains of radii 26 to 50 (results/calibration/passage.toml, which
  /// also sets those grains).
  static DropletParams passage();
  // How each of these compares with the defaults and with the paper: results/calibration/README.md.

  bool IsValid(std::string* why) const;
};

/// Which stages read a DropletParams field, and so which droplets can be stepped together:
/// - constraint: the length constraint (ring size, rest length, strain limit, passes); rings
///   constrained side by side must agree on these;
/// - forces: the other stages that can run for several droplets at once (gravity, springs, gas,
///   viscosity, integration, the constraint's order); droplets stepped as one block must agree on
///   these and the constraint's;
/// - contacts: read droplet by droplet (collisions, the contact limit, the medium's vibration).
enum class FieldUse { constraint, forces, contacts };

/// The values a numeric field accepts on its own: finite, from lo to hi, each end included or not
/// (an infinite end: no bound). DropletParams::IsValid checks every field's range, then the limits
/// that join fields (stability of the time step).
struct FieldRange {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_included = true, hi_included = true;
};
/// Ranges by name: > lo, >= lo, and [lo, hi] with each end included or not.
constexpr FieldRange above(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, true}; }
constexpr FieldRange at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, true}; }
constexpr FieldRange between(double lo, bool lo_included, double hi, bool hi_included) {
  return {lo, hi, lo_included, hi_included};
}

/// One field of DropletParams: `key` is its command-line option (--key) and its key in stored
/// parameters, `use` the stages that read it, `help` its meaning and unit for --help, `range` the
/// values it accepts (not read for the enums).
struct DropletField {
  const char* key;
  FieldUse use;
  const char* help;
  FieldRange range = {};
};

/// The one list of DropletParams's fields: calls f(field, p.field...) for each field, in
/// declaration order, with that field of every p given (one struct to read or write it, two to
/// compare them). A new field goes here, and the command-line options, the stored parameters and
/// the checks of which droplets step together follow.
template <class F, class... Params>
void visit_droplet_fields(F&& f, Params&... p) {
  using U = FieldUse;
  constexpr double inf = std::numeric_limits<double>::infinity();
  f(DropletField{"masses", U::constraint, "N, masses on the ring", between(8, true, 100000, true)}, p.masses...);
  f(DropletField{"mass", U::forces, "m, mass of each point (mass units)", above(0)}, p.mass...);
  f(DropletField{"radius", U::constraint, "R, inflated droplet radius (length units)", above(0)}, p.radius...);
  f(DropletField{"nrt", U::forces, "nRT of the ideal gas, P = nRT/V (force x length)", above(0)}, p.nrt...);
  f(DropletField{"ks", U::forces, "Spring stiffness k_s (force/length)", at_least(0)}, p.ks...);
  f(DropletField{"kd", U::forces, "Spring damping k_d (force x time/length)", at_least(0)}, p.kd...);
  f(DropletField{"kc", U::contacts, "Collision penalty stiffness k_c (force/length)", above(0)}, p.kc...);
  f(DropletField{"cc", U::contacts, "Collision normal damping (force x time/length)", at_least(0)}, p.cc...);
  f(DropletField{"gravity", U::forces, "g_y, gravity along y (length/time^2)", between(-inf, true, inf, true)},
    p.gravity...);
  f(DropletField{"dt", U::forces, "Time step (time units)", between(0, false, 1e-2, true)}, p.dt...);
  f(DropletField{"max-strain", U::constraint, "Provot limit on |d - d0|/d0", between(0, false, 0.5, false)},
    p.max_strain...);
  f(DropletField{"constraint-iterations", U::constraint, "Passes of the Provot constraint per step",
                 between(0, true, 100, true)},
    p.constraint_iterations...);
  f(DropletField{"constraint-order", U::forces,
                 "sequential (the reference) or red-black (independent half-passes: faster steps, other rounding)"},
    p.constraint_order...);
  f(DropletField{"max-depth", U::contacts, "Contact limit: deepest a mass may sit inside a grain (length units)",
                 above(0)},
    p.max_depth...);
  f(DropletField{"viscosity", U::forces, "Internal viscosity nu, damps motion relative to rigid motion (1/time)",
                 at_least(0)},
    p.viscosity...);
  f(DropletField{"viscosity-dilation", U::forces,
                 "Share of nu acting on uniform dilation, the breathing mode (1: damped as any deformation; 0: spared)",
                 between(0, true, 1, true)},
    p.viscosity_dilation...);
  f(DropletField{"viscosity-step", U::forces,
                 "explicit (nu's force integrated as the others, nu dt <= 0.5), exponential "
                 "(deformation decays by exp(-nu dt) a step: any nu dt) or implicit (backward Euler "
                 "after the other forces: any nu dt, and a pushed ring deforms at the continuous rate)"},
    p.viscosity_step...);
  f(DropletField{"vibration-amplitude", U::contacts,
                 "Shaking of the medium: its grains move by A (1 - cos 2 pi f t) (length units; 0: no shaking)",
                 at_least(0)},
    p.vibration_amplitude...);
  f(DropletField{"vibration-frequency", U::contacts, "Shaking frequency f (1/time units)", at_least(0)},
    p.vibration_frequency...);
  f(DropletField{"vibration-axis", U::contacts, "Shaking direction: x, y, or xy (both, in phase)"},
    p.vibration_axis...);
  f(DropletField{"vibration-start", U::contacts,
                 "When shaking begins: rest (when the run first finds the droplet at rest or stuck) or start"},
    p.vibration_start...);
}

/// Whether a and b agree, to the bit, on every field whose use is `use` or one of the uses listed
/// before it in FieldUse (constraint: the constraint's fields; forces: those and the force stages';
/// contacts: every field).
inline bool same_fields(const DropletParams& a, const DropletParams& b, FieldUse use) {
  bool same = true;
  visit_droplet_fields(
      [&](const DropletField& field, const auto& x, const auto& y) {
        if (static_cast<int>(field.use) > static_cast<int>(use)) return;
        if constexpr (std::is_floating_point_v<std::decay_t<decltype(x)>>)
          same = same && std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
        else
          same = same && x == y;
      },
      a, b);
  return same;
}

/// Runtime state of one droplet: structure of arrays, index i is mass i, ring order i -> i+1 is
/// counter-clockwise. Position Verlet keeps the previous positions; velocity is (x - px) / dt.
struct DropletState {
  std::vector<double> x, y;    ///< positions (x unwrapped: a periodic droplet never jumps)
  std::vector<double> px, py;  ///< positions one step earlier
  std::vector<double> fx, fy;  ///< force accumulators

  void resize(int n);
  int size() const { return static_cast<int>(x.size()); }
};

/// Places the droplet as the regular N-gon of circumradius resting_radius() centred at (cx, cy),
/// at rest: a droplet whose springs carry the tension starts without breathing.
void place_droplet(const DropletParams& params, double cx, double cy, DropletState* state);

/// Provot's inverse-dynamics length constraint on the ring's springs: every spring longer than
/// (1 + max_strain) d0 or shorter than (1 - max_strain) d0 has its two ends moved symmetrically
/// along it back to the limit, edge by edge in ring order (or even edges, then odd edges, then,
/// for an odd ring, the closing edge: red-black), for up to `iterations` passes (stops early once
/// a pass changes nothing). Previous positions are untouched, so Verlet's implied
/// velocities follow the corrected positions. Returns the number of corrections made.
int apply_length_constraint(DropletState* state, double rest_length, double max_strain, int iterations,
                            ConstraintOrder order = ConstraintOrder::sequential);

/// Signed enclosed area (shoelace), positive for counter-clockwise order.
double ring_area(const DropletState& state);

/// True if two non-adjacent edges of the ring intersect.
bool ring_self_intersects(const DropletState& state);

/// True if the point is inside the ring (crossing number).
bool ring_contains(const DropletState& state, double px, double py);

}  // namespace softdrop
