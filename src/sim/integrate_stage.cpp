// The integration stage of a droplet's step (kStepStages, step_stages.hpp): position Verlet,
// x' = 2 x - x_prev + dt^2 f / m, the kernel of stage_kernels.inc at width 1 on the ring's own
// arrays (the lane block runs the same kernel eight rings at a time).
#include "lane_scalar.hpp"
#include "ring_stages.hpp"
#include "step_context.hpp"

namespace softdrop {

void integrate_stage(const DropletModel& m, DropletRuntime& r) {
  r.changed();
  lanes::scalar::verlet_lanes(m.context.h2m, r.state.x.data(), r.state.y.data(), r.state.px.data(), r.state.py.data(),
                              r.state.fx.data(), r.state.fy.data(), r.state.size());
}

}  // namespace softdrop
