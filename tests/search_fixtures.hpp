#pragma once
// A small search scene shared by the search and history tests: 16 non-overlapping grains of radii
// 8 to 16 in a 160 x 120 periodic box; the balloon droplet (fixtures.hpp) passes through it
// (T0 ~ 1.25) in about 20 ms.

#include "fixtures.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/search.hpp"

namespace softdrop::test {

inline SearchOptions small_search_options(int lambda = 1) {
  SearchOptions o;
  o.lambda = lambda;
  o.seed = 7;
  o.droplet = balloon_droplet();
  o.run.stuck_window = 0.1;  // stuck droplets end sooner; the tests need many evaluations
  o.run.stuck_distance = 1;
  return o;
}

inline Medium small_search_medium() {
  MediumOptions m;
  m.kind = MediumKind::non_overlapping;
  m.grains = 16;
  m.width = 160;
  m.height = 120;
  m.r_min = kBalloonRMin;
  m.r_max = kBalloonRMax;
  m.seed = 2;  // medium seed 1 traps the droplet under these exit conditions
  return generate_medium(m);
}

/// Generation 0 of a search on the small medium: the configuration a search starts from.
inline Configuration small_search_start(const SearchOptions& o) {
  Configuration best;
  initial_generation(small_search_medium(), o, &best);
  return best;
}

}  // namespace softdrop::test
