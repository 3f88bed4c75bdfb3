// The step's constants from a droplet's parameters (step_context.hpp).
#include "step_context.hpp"

namespace softdrop {

StepContext make_step_context(const DropletParams& p) {
  StepContext k;
  k.weight = p.mass * p.gravity;
  k.ks = p.ks;
  k.kd = p.kd;
  k.inv_dt = 1.0 / p.dt;
  k.rest_length = p.rest_length();
  k.half_nrt = 0.5 * p.nrt;
  k.damped = p.viscosity > 0;
  k.viscous = p.mass * p.viscous_rate();
  k.spared_dilation = 1.0 - p.viscosity_dilation;
  k.kick = p.viscosity_step == ViscosityStep::implicit ? p.dt * p.dt / p.mass : 0.0;
  k.h2m = p.dt * p.dt / p.mass;
  k.dmax = (1 + p.max_strain) * k.rest_length;  // as apply_length_constraint takes them
  k.dmin = (1 - p.max_strain) * k.rest_length;
  return k;
}

}  // namespace softdrop
