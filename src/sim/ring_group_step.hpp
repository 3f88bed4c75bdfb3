#pragma once
// RingGroup: rings stepped side by side, each on its own arrays, as a layout of the step driver
// (step_driver.hpp). run_interleaved steps the droplets that are not in a lane-by-lane block so.
#include <vector>

#include "ring_contact.hpp"
#include "softdrop/simulation.hpp"
#include "step_driver.hpp"

namespace softdrop {

// Each stage runs for each ring in turn, as the ring's own step runs it (OneRing), but for the
// constraint: the sequential constraints of the rings that share the first sequential ring's
// constraint parameters go together (apply_length_constraint_interleaved: as lanes of the
// lane-by-lane block's constraint, where there are enough); every other ring is constrained alone;
// and the ring-ring stages, which run between the two rings of each pair. Each ring gets the bits
// of its own step(), or of its pair's.
struct RingGroup {
  Simulation* const* sims = nullptr;
  int count = 0;
  std::vector<DropletState*>* rings = nullptr;  // the constraint's scratch
  std::vector<int>* corrections = nullptr;      // the constraint's scratch
  RingPair* pairs = nullptr;                    // two droplets in one medium, each ring in one at most
  int pair_count = 0;

  static constexpr bool kRingPairs = true;

  // The rings may have different parameters and shaking: each ring's own pass through the driver
  // decides whether its viscosity and vibration stages run.
  bool damped() const { return true; }
  bool shaken() const { return true; }
  template <StepStage S>
  void stage() {
    if constexpr (S == StepStage::constraint) {
      constrain();
    } else if constexpr (S == StepStage::ring_contacts) {
      for (int q = 0; q < pair_count; ++q) ring_contacts(pairs[q]);
    } else if constexpr (S == StepStage::ring_limit) {
      for (int q = 0; q < pair_count; ++q) ring_limit(pairs[q]);
    } else {
      for (int t = 0; t < count; ++t) {
        OneRing ring(*sims[t]);
        step_driver_detail::run_stage<OneRing, S>(ring);  // the driver's test of the stage, for this ring
      }
    }
  }
  void constrain();
  void ring_contacts(RingPair& pair);
  void ring_limit(RingPair& pair);
};

}  // namespace softdrop
