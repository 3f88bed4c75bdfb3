// The scene the benchmarks share: the medium-200 medium (overlapping grains, porosity 0.7, a
// 500 x 500 box, seed 1: about 200 grains) and a droplet that has fallen into it.
#pragma once

#include <memory>

#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::bench {

/// medium-200, or the same grain density in a box `side` wide and high (medium-5000: 2500), of
/// the default grain radii or others.
inline Medium medium_200(double side = 500, double r_min = MediumOptions{}.r_min, double r_max = MediumOptions{}.r_max) {
  MediumOptions mo;
  mo.porosity = 0.7;
  mo.width = mo.height = side;
  mo.r_min = r_min;
  mo.r_max = r_max;
  mo.seed = 1;
  return generate_medium(mo);
}

/// A droplet dropped at x = 137 that has fallen into `medium` for 3 000 steps, so it touches
/// grains, with its forces computed: the state the stage benchmarks time their stage on.
inline std::unique_ptr<Simulation> droplet_in_contact(const DropletParams& params, const Medium& medium) {
  auto sim = std::make_unique<Simulation>(params, medium);
  sim->place_above(137);
  for (int i = 0; i < 3000; ++i) sim->step();
  sim->compute_forces();
  return sim;
}

}  // namespace softdrop::bench
