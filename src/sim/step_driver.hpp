#pragma once
// The one driver of the step: the stages of kStepStages (step_stages.hpp), in their order,
// over a layout of droplets. Private to the library.
//
// A layout is droplets laid out one way in memory, with an entry point for each stage:
//   bool damped() const         whether its droplets have internal viscosity (the viscosity stage
//                               runs only then; a layout of droplets of several parameters says
//                               true and lets each droplet's own pass decide)
//   bool shaken() const         whether the medium shakes for any of its droplets (the vibration
//                               stage runs only then)
//   template <StepStage S> void stage()
//                               stage S for every droplet of the layout
//   static constexpr bool kRingPairs (optional)
//                               true: the layout may hold pairs of rings of two droplets in one
//                               medium (RingPair, ring_contact.hpp), and the ring-ring stages run
//                               between each pair's rings; a layout without it has no code for them
// The layouts: one ring (OneRing, below), a block of droplets in vector lanes (lane_block_step.cpp)
// and rings stepped one after another, their constraints together (ring_group_step.cpp); the last
// two hold pairs. Each
// runs the same kernels for a stage, so every droplet gets the same bits in every layout; the
// golden state hashes hold them to it (tests/layout_hash_test.cpp).
#include "ring_stages.hpp"
#include "softdrop/simulation.hpp"
#include "step_context.hpp"
#include "step_stages.hpp"
#include "step_test_seam.hpp"

namespace softdrop {

namespace step_driver_detail {
template <class Layout>
constexpr bool ring_pairs() {
  if constexpr (requires { Layout::kRingPairs; })
    return Layout::kRingPairs;
  else
    return false;
}

template <class Layout, StepStage S>
void run_stage(Layout& layout) {
  if constexpr (S == StepStage::ring_contacts || S == StepStage::ring_limit) {
    if constexpr (ring_pairs<Layout>()) layout.template stage<S>();
  } else {
    if constexpr (S == StepStage::viscosity) {
      if (!layout.damped()) return;
    }
    if constexpr (S == StepStage::vibration) {
      if (!layout.shaken()) return;
    }
    layout.template stage<S>();
  }
}
}  // namespace step_driver_detail

/// Runs the stages from `first` to `last` of kStepStages over `layout`, in their order.
template <class Layout>
void run_stages(Layout& layout, StepStage first = StepStage::gravity, StepStage last = StepStage::ring_limit) {
#if defined(SOFTDROP_TEST_HOOKS)
  if (test_seam::step_mutation() == test_seam::StepMutation::damps_before_collisions && first == StepStage::gravity &&
      last >= StepStage::integrate) {
    // The seam's drifted order: the viscosity stage moved before the collisions.
    run_step_stages([&](auto s) { step_driver_detail::run_stage<Layout, decltype(s)::value>(layout); },
                    StepStage::gravity, StepStage::pressure);
    step_driver_detail::run_stage<Layout, StepStage::viscosity>(layout);
    step_driver_detail::run_stage<Layout, StepStage::collisions>(layout);
    step_driver_detail::run_stage<Layout, StepStage::ring_contacts>(layout);
    run_step_stages([&](auto s) { step_driver_detail::run_stage<Layout, decltype(s)::value>(layout); },
                    StepStage::integrate, last);
    return;
  }
#endif
  run_step_stages([&](auto s) { step_driver_detail::run_stage<Layout, decltype(s)::value>(layout); }, first, last);
}

/// One droplet's ring, on its own arrays (Simulation::step).
struct OneRing {
  const DropletModel& m;
  DropletRuntime& r;

  explicit OneRing(Simulation& sim) : m(sim.model()), r(sim.runtime()) {}
  OneRing(const DropletModel& model, DropletRuntime& runtime) : m(model), r(runtime) {}
  bool damped() const { return m.context.damped; }
  bool shaken() const { return r.shake.on; }
  template <StepStage S>
  void stage() {
    if constexpr (S == StepStage::gravity)
      gravity_stage(m, r);
    else if constexpr (S == StepStage::vibration)
      vibration_stage(m, r);
    else if constexpr (S == StepStage::springs)
      springs_stage(m, r);
    else if constexpr (S == StepStage::pressure)
      pressure_stage(m, r);
    else if constexpr (S == StepStage::collisions)
      collisions_stage(m, r, r.state.fx.data(), r.state.fy.data(), 1, /*recorded_added=*/false);
    else if constexpr (S == StepStage::viscosity)
      viscosity_stage(m, r);
    else if constexpr (S == StepStage::integrate)
      integrate_stage(m, r);
    else if constexpr (S == StepStage::constraint)
      constraint_stage(m, r);
    else if constexpr (S == StepStage::contact_limit)
      contact_limit_stage(m, r);
    else
      static_assert(S != S, "a stage without code");
  }
};

/// One stage of sim's step, on its own (what step() runs for it; the viscosity only where nu > 0):
/// for tests and benchmarks that check or time a stage.
inline void run_stage(Simulation& sim, StepStage stage) {
  OneRing ring(sim);
  run_stages(ring, stage, stage);
}
/// run_stage for a stage known at compile time.
template <StepStage S>
void run_stage(Simulation& sim) {
  OneRing ring(sim);
  step_driver_detail::run_stage<OneRing, S>(ring);
}

}  // namespace softdrop
