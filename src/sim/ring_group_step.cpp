// The constraint stage of rings stepped side by side (ring_group_step.hpp).
#include "ring_group_step.hpp"

#include "droplet_model.hpp"
#include "lane_policy.hpp"
#include "ring_stages.hpp"

namespace softdrop {

void RingGroup::constrain() {
  rings->clear();
  const DropletModel* first = nullptr;  // the first sequential ring's
  for (int t = 0; t < count; ++t) {
    const DropletModel& m = sims[t]->model();
    DropletRuntime& r = sims[t]->runtime();
    if (m.params.constraint_order == ConstraintOrder::sequential) {
      if (!first) first = &m;
      if (same_fields(first->params, m.params, FieldUse::constraint)) {
        r.changed();
        rings->push_back(&r.state);
        continue;
      }
    }
    constraint_stage(m, r);
  }
  if (rings->empty()) return;
  corrections->resize(rings->size());
  apply_length_constraint_interleaved(rings->data(), static_cast<int>(rings->size()), first->context.rest_length,
                                      first->params.max_strain, first->params.constraint_iterations,
                                      corrections->data());
}

}  // namespace softdrop
