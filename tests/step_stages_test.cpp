// The step as one list of named stages (step_stages.hpp): the list, its parts, and Simulation::step
// as exactly the stages' own functions in the list's order.
#include "sim/step_stages.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "fixtures.hpp"
#include "sim/ring_stages.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

TEST(StepStages, TheListHasEveryStageOnceInTheEnumsOrderWithDistinctNames) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kStepStages.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(kStepStages[i]), i);
    names.insert(to_string(kStepStages[i]));
  }
  EXPECT_EQ(names.size(), kStepStages.size());
  EXPECT_STREQ(to_string(StepStage::gravity), "gravity");
  EXPECT_STREQ(to_string(StepStage::contact_limit), "contact_limit");
}

TEST(StepStages, APartRunsItsStagesInOrderAndNoOthers) {
  std::vector<StepStage> seen;
  run_step_stages([&](StepStage s) { seen.push_back(s); }, StepStage::collisions, StepStage::constraint);
  EXPECT_EQ(seen, (std::vector<StepStage>{StepStage::collisions, StepStage::ring_contacts, StepStage::viscosity,
                                          StepStage::integrate, StepStage::constraint}));
  seen.clear();
  run_step_stages([&](StepStage s) { seen.push_back(s); });
  EXPECT_EQ(seen, std::vector<StepStage>(kStepStages.begin(), kStepStages.end()));
  // Parts make up the whole step.
  seen.clear();
  auto add = [&](StepStage s) { seen.push_back(s); };
  run_step_stages(add, StepStage::gravity, StepStage::integrate);
  run_step_stages(add, StepStage::constraint, StepStage::constraint);
  run_step_stages(add, StepStage::contact_limit, StepStage::ring_limit);
  EXPECT_EQ(seen, std::vector<StepStage>(kStepStages.begin(), kStepStages.end()));
}

// Steps `a` with step() and `b` with the stages' functions called by hand in `order`, through
// the pore of three grains (contacts, squeezing, the contact limit at work), and returns the
// first step after which they differ (0: none in `steps`).
int first_difference(Simulation* a, Simulation* b, const std::vector<StepStage>& order, int steps) {
  a->place_above(100.0);
  b->place_above(100.0);
  for (int k = 1; k <= steps; ++k) {
    a->step();
    const DropletModel& m = b->model();
    DropletRuntime& r = b->runtime();
    for (StepStage s : order) {
      switch (s) {
        case StepStage::gravity:
          gravity_stage(m, r);
          break;
        case StepStage::springs:
          springs_stage(m, r);
          break;
        case StepStage::pressure:
          pressure_stage(m, r);
          break;
        case StepStage::vibration:
          if (r.shake.on) vibration_stage(m, r);
          break;
        case StepStage::collisions:
          collisions_stage(m, r, r.state.fx.data(), r.state.fy.data(), 1, /*recorded_added=*/false);
          break;
        case StepStage::viscosity:
          if (b->params().viscosity > 0) viscosity_stage(m, r);
          break;
        case StepStage::integrate:
          integrate_stage(m, r);
          break;
        case StepStage::constraint:
          constraint_stage(m, r);
          break;
        case StepStage::contact_limit:
          contact_limit_stage(m, r);
          break;
        case StepStage::ring_contacts:  // one droplet: no other ring
        case StepStage::ring_limit:
          break;
      }
    }
    if (a->state_hash() != b->state_hash()) return k;
  }
  return 0;
}

TEST(StepStages, AStepIsTheStagesFunctionsInTheListsOrder) {
  const Medium pore = test::pore_of_three_grains();
  const std::vector<StepStage> order(kStepStages.begin(), kStepStages.end());
  for (double viscosity : {0.0, 3000.0}) {
    for (ConstraintOrder constraint : {ConstraintOrder::sequential, ConstraintOrder::red_black}) {
      DropletParams p = test::balloon_droplet();  // (the pore and the step count were laid out for it)
      p.viscosity = viscosity;
      p.constraint_order = constraint;
      Simulation a(p, pore), b(p, pore);
      EXPECT_EQ(first_difference(&a, &b, order, 3000), 0) << "viscosity " << viscosity;
      double cx, cy;
      a.centre_of_mass(&cx, &cy);
      EXPECT_LT(cy, pore.grains[0].y);  // it went through the pore, touching its grains
    }
  }
}

TEST(StepStages, TheOrderMatters) {
  // The same stages with the constraint before the integration, or the pressure before the
  // springs, give other bits: the comparison above can see a wrong order.
  const Medium pore = test::pore_of_three_grains();
  const DropletParams p = test::balloon_droplet();
  std::vector<StepStage> swapped(kStepStages.begin(), kStepStages.end());
  std::swap(swapped[6], swapped[7]);  // integrate, constraint
  Simulation a(p, pore), b(p, pore);
  EXPECT_GT(first_difference(&a, &b, swapped, 3000), 0);
  std::vector<StepStage> late(kStepStages.begin(), kStepStages.end());
  std::swap(late[1], late[2]);  // springs, pressure
  Simulation c(p, pore), d(p, pore);
  EXPECT_GT(first_difference(&c, &d, late, 3000), 0);
}

}  // namespace
}  // namespace softdrop
