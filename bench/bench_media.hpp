// The scene the benchmarks share: the medium-200 medium (overlapping grains, porosity 0.7, a
// 500 x 500 box, seed 1: about 200 grains) and a droplet that has fallen into it.
#pragma once

#include <memory>
#include <stdexcept>

#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::bench {

/// medium-200, or the same grain density in a box `side` wide and high (medium-5000: 2500), of
/// the default grain radii or others.
inline Medium medium_200(double side = 500, double r_min = MediumOptions{}.r_min,
                         double r_max = MediumOptions{}.r_max) {
  MediumOptions mo;
  mo.porosity = 0.7;
  mo.width = mo.height = side;
  mo.r_min = r_min;
  mo.r_max = r_max;
  mo.seed = 1;
  return generate_medium(mo);
}

/// A droplet dropped at x = 428, where it lands on grains of medium-200, stepped until a mass first
/// touches a grain, then 4 000 steps more (0.014 time units at the defaults' dt), then on to the
/// next step in which a mass touches a grain, with its forces computed: the state the stage
/// benchmarks time their stage on. Contact is what makes the collision and contact-limit stages do
/// their work, so it is found, not assumed from a fixed number of steps (a count right for one dt
/// is free fall at another). Throws if no contact comes within 100 000 steps.
inline std::unique_ptr<Simulation> droplet_in_contact(const DropletParams& params, const Medium& medium) {
  auto sim = std::make_unique<Simulation>(params, medium);
  sim->place_above(428);
  const auto step_to_contact = [&sim] {
    for (int steps = 0; sim->last_penetration() <= 0; ++steps) {
      if (steps == 100000) throw std::runtime_error("droplet_in_contact: no grain touched in 100 000 steps");
      sim->step();
    }
  };
  step_to_contact();
  for (int i = 0; i < 4000; ++i) sim->step();
  step_to_contact();
  sim->compute_forces();
  return sim;
}

}  // namespace softdrop::bench
