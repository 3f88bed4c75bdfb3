#include "contact_cache.hpp"

#include <limits>

namespace softdrop {

void ContactCache::reset(std::size_t masses, std::size_t disc_capacity, std::int32_t no_grain) {
  capacity = disc_capacity;
  discs.assign(masses * capacity, GrainGrid::Disc{});
  count.assign(masses, 0);
  x.assign(masses, std::numeric_limits<double>::quiet_NaN());  // matches no position
  y.assign(masses, std::numeric_limits<double>::quiet_NaN());
  clear_x.assign(masses, 0.0);
  clear_y.assign(masses, 0.0);
  clear_r2.assign(masses, -1.0);
  clear_count.assign(masses, 0);
  clear_discs.assign(discs.size(), GrainGrid::Disc{});
  for (std::vector<double>* v : {&disc_x, &disc_y, &disc_r}) v->assign(masses, 0.0);
  disc_grain.assign(masses, 0);
  fx.assign(masses, -0.0);
  fy.assign(masses, -0.0);
  touch.assign(masses, no_grain);
  todo.clear();
  todo.reserve(masses);
  deepest = 0;
  current = false;
}

}  // namespace softdrop
