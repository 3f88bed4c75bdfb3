// The constraint stage of rings stepped side by side (ring_group_step.hpp).
#include "ring_group_step.hpp"

#include "droplet_model.hpp"
#include "lane_policy.hpp"
#include "ring_stages.hpp"

namespace softdrop {

void RingGroup::constrain() {
  rings->clear();
  const Simulation* first = nullptr;
  for (int t = 0; t < count; ++t) {
    Simulation* sim = sims[t];
    if (sim->params().constraint_order == ConstraintOrder::sequential) {
      if (!first) first = sim;
      if (same_fields(first->params(), sim->params(), FieldUse::constraint)) {
        rings->push_back(&sim->mutable_state());
        continue;
      }
    }
    constraint_stage(sim->model(), sim->runtime());
  }
  if (rings->empty()) return;
  corrections->resize(rings->size());
  apply_length_constraint_interleaved(rings->data(), static_cast<int>(rings->size()),
                                      first->model().context.rest_length, first->params().max_strain,
                                      first->params().constraint_iterations, corrections->data());
}

}  // namespace softdrop
