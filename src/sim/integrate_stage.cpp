// The integration stage of a droplet's step (kStepStages, step_stages.hpp): position Verlet,
// x' = 2 x - x_prev + dt^2 f / m, the kernel of stage_kernels.inc at width 1 on the ring's own
// arrays (the lane block runs the same kernel eight rings at a time).
#include "lane_scalar.hpp"
#include "softdrop/simulation.hpp"
#include "step_context.hpp"

namespace softdrop {

void Simulation::integrate() {
  state_changed();
  lanes::scalar::verlet_lanes(context_->h2m, state_.x.data(), state_.y.data(), state_.px.data(), state_.py.data(),
                              state_.fx.data(), state_.fy.data(), state_.size());
}

}  // namespace softdrop
