// The constraint and ring-ring stages of rings stepped side by side (ring_group_step.hpp).
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
      // (Copies of one simulation share its model: no fields to compare.)
      if (&m == first || same_fields(first->params, m.params, FieldUse::constraint)) {
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

void RingGroup::ring_contacts(RingPair& pair) {
  DropletRuntime &a = sims[pair.a]->runtime(), &b = sims[pair.b]->runtime();
  ring_contacts_stage(sims[pair.a]->model(), a, b, pair.scratch, RingForces::of(a), RingForces::of(b));
}

void RingGroup::ring_limit(RingPair& pair) {
  pair.moved = ring_limit_stage(sims[pair.a]->model(), sims[pair.a]->runtime(), sims[pair.b]->runtime(), pair.scratch);
}

}  // namespace softdrop
