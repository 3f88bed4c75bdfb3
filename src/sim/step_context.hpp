#pragma once
// The step's constants, derived from a droplet's parameters in one place (make_step_context) and
// read by every layout of the step: one ring (Simulation) and a block of droplets in vector lanes
// (lane_block_step.cpp) take the same bits from the same object. Private to the library.
#include "softdrop/droplet.hpp"

namespace softdrop {

struct StepContext {
  double weight = 0;           ///< m g_y, each mass's y force before the others (force)
  double ks = 0, kd = 0;       ///< spring stiffness (force/length) and damping (force time/length)
  double inv_dt = 0;           ///< 1 / dt (1/time)
  double rest_length = 0;      ///< d0, the springs' rest length (length)
  double half_nrt = 0;         ///< 0.5 nRT: the pressure's force on each edge end is 0.5 nRT / area
  bool damped = false;         ///< whether the droplet has internal viscosity (nu > 0): the stage runs
  double viscous = 0;          ///< m times the viscosity step's rate
  double spared_dilation = 0;  ///< 1 - viscosity_dilation: the share of uniform dilation not damped
  /// dt^2 / m with the implicit viscosity step, whose damped velocity is the one after this step's
  /// other forces (x - px + kick F at the viscosity stage); 0 for the other steps.
  double kick = 0;
  double h2m = 0;  ///< dt^2 / m (position Verlet)
  /// The length constraint's limits, (1 - max_strain) d0 and (1 + max_strain) d0 (length).
  double dmin = 0, dmax = 0;
};

/// The constants of droplets of parameters p.
StepContext make_step_context(const DropletParams& p);

}  // namespace softdrop
