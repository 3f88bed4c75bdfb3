#pragma once
/// \file step_stages.hpp
/// The physics stages of one time step, in their order. The step's one driver (step_driver.hpp)
/// runs this list over each layout of droplets: one ring (Simulation::step), a block of droplets
/// side by side in vector lanes, and rings stepped side by side, each layout with its entry point
/// for a stage (docs/code-layout.md names each stage's file). Private to the library. A run
/// follows every step with its exit tests (passed, stuck, at rest, diverged, out of steps).

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace softdrop {

enum class StepStage : std::uint8_t {
  gravity,        ///< the forces cleared to each mass's weight m g
  springs,        ///< damped springs along the ring: k_s (d - d0) + k_d (relative velocity)
  pressure,       ///< the gas, P = nRT / S, on each edge along its outward normal
  vibration,      ///< the shaken medium's inertial force on each mass (only while it shakes)
  collisions,     ///< penalty and damping against grains and walls; the touched grains
  ring_contacts,  ///< penalty and damping between two droplets' rings (only where two droplets run)
  viscosity,      ///< internal viscosity relative to the rigid motion (only where ν > 0); last of the forces
  integrate,      ///< position Verlet
  constraint,     ///< the Provot length constraint, in the droplet's constraint order
  contact_limit,  ///< inverse dynamics: no mass deeper than max_depth inside a grain
  ring_limit,     ///< inverse dynamics: no mass of two droplets' rings inside the other (as ring_contacts)
};

/// Every stage of a step, in order.
inline constexpr std::array<StepStage, 11> kStepStages{
    StepStage::gravity,    StepStage::springs,       StepStage::pressure,  StepStage::vibration,
    StepStage::collisions, StepStage::ring_contacts, StepStage::viscosity, StepStage::integrate,
    StepStage::constraint, StepStage::contact_limit, StepStage::ring_limit};

// The implicit viscosity step damps the velocity after every other force of the step, which it
// reads from the force arrays: viscosity must come after the other force stages, just before
// the integration.
static_assert(kStepStages[6] == StepStage::viscosity && kStepStages[7] == StepStage::integrate,
              "the viscosity stage must be the last force stage (the implicit step reads the others' forces)");

/// The stage's name, as above ("gravity", ..., "ring_limit").
const char* to_string(StepStage stage);

namespace step_stages_detail {
template <class Run, std::size_t... I>
constexpr void run_in_order(Run& run, StepStage first, StepStage last, std::index_sequence<I...>) {
  ((kStepStages[I] >= first && kStepStages[I] <= last ? run(std::integral_constant<StepStage, kStepStages[I]>{})
                                                      : void()),
   ...);
}
}  // namespace step_stages_detail

/// Calls run(stage) for the stages from `first` to `last` of kStepStages, in their order. A
/// stepper that runs a step in parts (the constraint of several rings together) calls it once
/// for each part. Each stage comes as a std::integral_constant<StepStage, stage>, which converts
/// to StepStage; a stepper may read it at compile time (decltype(stage)::value), so that a step
/// is its stages' calls one after another, with no choice among them at run time.
template <class Run>
constexpr void run_step_stages(Run&& run, StepStage first = StepStage::gravity,
                               StepStage last = StepStage::ring_limit) {
  step_stages_detail::run_in_order(run, first, last, std::make_index_sequence<kStepStages.size()>{});
}

}  // namespace softdrop
