#pragma once
// TwoRings: the rings of two droplets in one medium, stepped together as a layout of the step
// driver (step_driver.hpp), with the ring-ring stages between them. Private to the library.
#include "ring_contact.hpp"
#include "step_driver.hpp"

namespace softdrop {

// Each stage runs for each ring in turn, as the ring's own step runs it (OneRing); the ring-ring
// stages run between the two. With one ring (b null: the second droplet not yet released, or one
// droplet gone), a step is that ring's own step, to the bit.
struct TwoRings {
  const DropletModel& m;
  DropletRuntime* a = nullptr;  ///< null: not stepped
  DropletRuntime* b = nullptr;  ///< null: not stepped
  RingContactScratch* scratch = nullptr;
  int moved = 0;  ///< masses the last ring_limit moved

  static constexpr bool kTwoRings = true;
  // Each ring's own pass through the driver decides whether its viscosity and vibration run.
  bool damped() const { return true; }
  bool shaken() const { return true; }
  template <StepStage S>
  void stage() {
    if constexpr (S == StepStage::ring_contacts) {
      if (a && b) ring_contacts_stage(m, *a, *b, scratch);
    } else if constexpr (S == StepStage::ring_limit) {
      moved = a && b ? ring_limit_stage(m, *a, *b, scratch) : 0;
    } else {
      for (DropletRuntime* r : {a, b}) {
        if (!r) continue;
        OneRing ring(m, *r);
        step_driver_detail::run_stage<OneRing, S>(ring);
      }
    }
  }
};

}  // namespace softdrop
