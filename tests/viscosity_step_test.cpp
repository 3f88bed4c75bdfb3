// The internal viscosity's three steps: the explicit force (1 - nu dt a step), the exponential
// one (exp(-nu dt) a step, the exact decay) and the implicit one (backward Euler on the velocity
// after the other forces: a steadily pushed ring deforms at the continuous rate), their limits,
// and the option's names.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "cli_run.hpp"
#include "fixtures.hpp"
#include "sim/step_driver.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

// A ring at rest positions moving rigidly (translation u, rotation omega) plus a shear of rate a,
// (a r_x, -a r_y): a deformation with no momentum, no angular momentum and no dilation. After the
// viscosity and integration stages alone, returns the largest misfit of the new velocities against
// the rigid motion plus `factor` times the shear, over the largest shear speed. `push` adds a
// shearing force m push (r_x, -r_y) before the viscosity (no net force or torque on the ring).
double shear_misfit(const DropletParams& p, double factor, double push = 0) {
  const Medium empty = test::empty_medium();
  Simulation sim(p, empty);
  sim.place(250, 250);
  DropletState& s = sim.mutable_state();
  const double dt = p.dt, omega = 40, ux = 300, uy = -200, a = 2000;
  auto rigid_x = [&](double, double ry) { return ux - omega * ry; };
  auto rigid_y = [&](double rx, double) { return uy + omega * rx; };
  std::vector<double> rx(s.size()), ry(s.size());
  for (int i = 0; i < s.size(); ++i) {
    rx[i] = s.x[i] - 250, ry[i] = s.y[i] - 250;
    s.px[i] = s.x[i] - dt * (rigid_x(rx[i], ry[i]) + a * rx[i]);
    s.py[i] = s.y[i] - dt * (rigid_y(rx[i], ry[i]) - a * ry[i]);
  }
  run_stage(sim, StepStage::gravity);  // clears the forces (no gravity)
  for (int i = 0; i < s.size(); ++i) s.fx[i] += p.mass * push * rx[i], s.fy[i] -= p.mass * push * ry[i];
  run_stage(sim, StepStage::viscosity);
  run_stage(sim, StepStage::integrate);
  double worst = 0;
  for (int i = 0; i < s.size(); ++i) {
    const double vx = (s.x[i] - s.px[i]) / dt, vy = (s.y[i] - s.py[i]) / dt;
    worst = std::max(worst, std::hypot(vx - rigid_x(rx[i], ry[i]) - factor * a * rx[i],
                                       vy - rigid_y(rx[i], ry[i]) + factor * a * ry[i]));
  }
  return worst / (a * p.resting_radius());
}

// The droplet at explicit_step()'s dt, 3.5e-6, without gravity.
DropletParams weightless(ViscosityStep step, double viscosity) {
  DropletParams p = DropletParams::explicit_step();
  p.gravity = 0;
  p.viscosity_dilation = 1;
  p.viscosity_step = step;
  p.viscosity = viscosity;
  return p;
}

TEST(ViscosityStep, TheExplicitStepTakesOneMinusNuDtOfTheDeformationAStep) {
  const DropletParams p = weightless(ViscosityStep::explicit_euler, 1.37e5);  // nu dt = 0.4795
  EXPECT_LT(shear_misfit(p, 1 - p.viscosity * p.dt), 1e-8);
  EXPECT_GT(shear_misfit(p, std::exp(-p.viscosity * p.dt)), 0.05);  // (the two differ by 0.099)
}

TEST(ViscosityStep, TheExponentialStepTakesTheExactDecayAtAnyNuDt) {
  for (double nu_dt : {1e-3, 0.4795, 3.5}) {
    SCOPED_TRACE("nu dt = " + std::to_string(nu_dt));
    const DropletParams p = weightless(ViscosityStep::exponential, nu_dt / 3.5e-6);
    EXPECT_LT(shear_misfit(p, std::exp(-nu_dt)), 1e-8);
  }
  // To first order in nu dt the two steps agree: the rates differ by nu^2 dt / 2.
  DropletParams slow = weightless(ViscosityStep::exponential, 10.0);
  const double explicit_rate = slow.viscosity;
  EXPECT_NEAR(slow.viscous_rate(), explicit_rate, 0.51 * explicit_rate * explicit_rate * slow.dt);
  EXPECT_LT(slow.viscous_rate(), explicit_rate);
  slow.viscosity_step = ViscosityStep::explicit_euler;
  EXPECT_EQ(slow.viscous_rate(), explicit_rate);  // the reference's coefficient, to the bit
}

// The implicit step: u' = (u + push dt) / (1 + nu dt) on the deformation. A ring shearing at
// push / nu, the rate at which the continuous viscosity balances the push, stays at it at every
// nu dt; the exponential step's steady rate is push / nu times nu dt / (1 - exp(-nu dt)).
TEST(ViscosityStep, TheImplicitStepDeformsASteadilyPushedRingAtTheContinuousRateAtAnyDt) {
  for (double nu_dt : {1e-3, 0.4795, 1.68, 20.0}) {
    SCOPED_TRACE("nu dt = " + std::to_string(nu_dt));
    const DropletParams p = weightless(ViscosityStep::implicit, nu_dt / 3.5e-6);
    const double shear = 2000, push = shear * p.viscosity;  // shear = push / nu
    EXPECT_LT(shear_misfit(p, 1.0, push), 1e-8);
    EXPECT_LT(shear_misfit(p, 1 / (1 + nu_dt)), 1e-8);  // unpushed: backward Euler's decay
    EXPECT_EQ(p.viscous_rate(), p.viscosity / (1 + nu_dt));
    DropletParams e = p;
    e.viscosity_step = ViscosityStep::exponential;
    EXPECT_LT(shear_misfit(e, std::exp(-nu_dt) + nu_dt, push), 1e-8);  // not steady: it drifts
    if (nu_dt > 0.1) {
      EXPECT_GT(std::abs(std::exp(-nu_dt) + nu_dt - 1), 0.09);
    }
  }
}

TEST(ViscosityStep, OnlyTheExplicitStepBoundsNuDt) {
  DropletParams p = weightless(ViscosityStep::explicit_euler, 1e6);  // nu dt = 3.5
  std::string why;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_EQ(why,
            "viscosity = 1e+06, dt = 3.5e-06: viscosity * dt = 3.5 must be <= 0.5 for "
            "viscosity-step explicit");
  p.viscosity_step = ViscosityStep::exponential;
  EXPECT_TRUE(p.IsValid(&why)) << why;
  p.viscosity_step = ViscosityStep::implicit;
  EXPECT_TRUE(p.IsValid(&why)) << why;
  p.dt = 1e-2;  // the springs still bound dt
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_EQ(why.rfind("dt = 0.01: too large for the stiffness", 0), 0u) << why;
}

TEST(ViscosityStep, AStrongExponentialViscosityKeepsTheRingWhole) {
  // nu dt = 6 (the defaults' dt): each step leaves 0.25 % of the deformation's velocity. The
  // droplet falls through an empty box as a rigid ring would, straight down; the explicit step
  // could not run it at all.
  DropletParams p;
  p.viscosity_step = ViscosityStep::exponential;
  p.viscosity = 1e6;
  const Medium empty = test::empty_medium();
  RunOptions o;
  o.area_interval = 100;
  const RunSummary r = Simulation(p, empty).run(250, o);
  ASSERT_EQ(r.outcome, Outcome::passed) << r.reason;
  EXPECT_NEAR(r.tortuosity, 1.0, 1e-9);
  EXPECT_GT(r.min_area_ratio, 1 - 1e-9);
}

// The largest deviation of the ring's area from its start over `steps` steps without gravity,
// from positions perturbed by 1e-7 (relative to the start area).
double perturbed_area_drift(const DropletParams& p, int steps) {
  DropletParams q = p;
  q.gravity = 0;
  const Medium empty = test::empty_medium();
  Simulation sim(q, empty);
  sim.place(250, 250);
  DropletState& s = sim.mutable_state();
  for (int i = 0; i < s.size(); ++i) s.x[i] += 1e-7 * (i % 2 == 0 ? 1 : -1) * (1 + 0.1 * i);
  const double a0 = sim.area();
  double worst = 0;
  for (int k = 0; k < steps; ++k) {
    if (!sim.step()) return INFINITY;
    worst = std::max(worst, std::abs(sim.area() / a0 - 1));
  }
  return worst;
}

// The time step at which 4 ks dt^2 / m + 2 (4 kd / m + rate) dt reaches `level`, by bisection.
double dt_at(DropletParams p, double level) {
  double lo = 1e-8, hi = 1e-4;
  for (int i = 0; i < 60; ++i) {
    p.dt = 0.5 * (lo + hi);
    const double a = 4 * p.ks * p.dt * p.dt / p.mass, b = (4 * p.kd / p.mass + p.viscous_rate()) * p.dt;
    (a + 2 * b < level ? lo : hi) = p.dt;
  }
  return lo;
}

TEST(ViscosityStep, TheRingsFastestModeBoundsDtWithTheSpringDampingAndTheViscosityTogether) {
  // Without viscosity the defaults at dt = 1.4e-5 pass the stiffness and damping checks one by one
  // (sqrt(ks / m) dt = 0.44, kd dt / m = 0.47), but the ring's fastest mode grows: refused.
  DropletParams p;
  p.viscosity = 0;
  p.dt = 1.4e-5;
  std::string why;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_EQ(why.rfind("dt = 1.4e-05: too large for the ring's fastest mode", 0), 0u) << why;
  EXPECT_NE(why.find("= 4.535"), std::string::npos) << why;
  // The bound is the boundary, not a margin: at 0.9 of it a perturbed ring stays whole, explicit
  // or exponential, with weak or strong viscosity.
  for (auto [step, nu] : {std::pair{ViscosityStep::explicit_euler, 0.0},
                          std::pair{ViscosityStep::exponential, 1.8656e5}, std::pair{ViscosityStep::exponential, 1e6},
                          std::pair{ViscosityStep::implicit, 1.37e5}, std::pair{ViscosityStep::implicit, 1e6}}) {
    DropletParams q;
    q.viscosity_step = step;
    q.viscosity = nu;
    q.dt = dt_at(q, 0.9 * 4);
    SCOPED_TRACE(std::string(to_string(step)) + ", nu = " + std::to_string(nu) + ", dt = " + std::to_string(q.dt));
    ASSERT_TRUE(q.IsValid(&why)) << why;
    EXPECT_LT(perturbed_area_drift(q, 3000), 1e-5);
    q.dt = dt_at(q, 4 * 1.0001);
    EXPECT_FALSE(q.IsValid(&why));
  }
}

TEST(ViscosityStep, TheOptionTakesItsNamesAndNamesABadOne) {
  EXPECT_EQ(parse_viscosity_step("exponential"), ViscosityStep::exponential);
  EXPECT_STREQ(to_string(ViscosityStep::explicit_euler), "explicit");
  EXPECT_EQ(parse_viscosity_step("implicit"), ViscosityStep::implicit);
  EXPECT_EQ(value_names(ViscosityStep{}), (std::vector<std::string>{"explicit", "exponential", "implicit"}));
  EXPECT_THROW(parse_viscosity_step("backward"), std::invalid_argument);
  const test::Result bad = test::run("simulate --x0 250 --viscosity-step backward");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("--viscosity-step"), std::string::npos) << bad.err;
  const test::Result refused = test::run("simulate --x0 250 --viscosity 1e6 --viscosity-step explicit --dt 3.5e-6");
  EXPECT_NE(refused.code, 0);
  EXPECT_NE(refused.err.find("viscosity * dt = 3.5 must be <= 0.5"), std::string::npos) << refused.err;
  const test::Result ran = test::run("simulate --x0 250 --viscosity 1e6 --dt 3.5e-6 --quiet");
  EXPECT_EQ(ran.code, 0) << ran.err;
}

}  // namespace
}  // namespace softdrop
