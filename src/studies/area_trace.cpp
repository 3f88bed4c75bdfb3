#include "area_trace.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/droplet_runtime.hpp"
namespace softdrop {

AreaTrace trace_area(const DropletParams& params, const Medium& medium, double x0, const RunOptions& run,
                     int interval) {
  if (interval < 1) throw std::invalid_argument("trace_area: interval must be >= 1");
  RunOptions plain = run;
  plain.area_interval = 0;  // (the replay records the area; the path, if asked for, is the run's)
  plain.snapshot_times.clear();
  Simulation sim(params, medium);
  AreaTrace trace;
  trace.run = sim.run(x0, plain);
  trace.enter = trace.leave = trace.s0 = trace.min_ratio = trace.max_ratio = NAN;
  // The replay: the run is deterministic, so these steps are the ones the summary describes.
  sim.place_above(x0);
  constexpr std::int64_t kFollow = 20000;  // steps to follow a passed droplet out of the medium
  const std::int64_t end = trace.run.outcome == Outcome::passed ? trace.run.steps + kFollow : trace.run.steps;
  double lo_ratio = INFINITY, hi_ratio = -INFINITY;
  // A shaken medium shakes the replay as it shook the run: each step after the one it began at,
  // with the force the run gave that step (and on while the trace follows a passed droplet out).
  const bool shaken = !std::isnan(trace.run.shaken_at);
  const std::int64_t shaken_after = shaken ? std::llround(trace.run.shaken_at / params.dt) : 0;
  for (std::int64_t step = 0; step <= end; ++step) {
    if (shaken && step > shaken_after)
      sim.runtime().shake.set(params, sim.state().size(), static_cast<double>(step - 1 - shaken_after) * params.dt);
    if (step > 0 && !sim.step()) break;
    const DropletState& st = sim.state();
    const double lowest = *std::min_element(st.y.begin(), st.y.end());
    const double highest = *std::max_element(st.y.begin(), st.y.end());
    const double time = static_cast<double>(step) * params.dt;
    if (std::isnan(trace.enter) && lowest <= medium.height) trace.enter = time, trace.s0 = sim.area();
    if (!std::isnan(trace.enter)) {
      lo_ratio = std::min(lo_ratio, sim.area() / trace.s0);
      hi_ratio = std::max(hi_ratio, sim.area() / trace.s0);
    }
    const bool left = highest < 0;
    if (step % interval == 0 || left) trace.t.push_back(time), trace.area.push_back(sim.area());
    if (left) {
      trace.leave = time;
      break;
    }
  }
  if (!std::isnan(trace.enter)) trace.min_ratio = lo_ratio, trace.max_ratio = hi_ratio;
  return trace;
}

}  // namespace softdrop
