// DropletModel: the part of a simulation its droplets share, built and checked in one place.
#include "droplet_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "util/validation.hpp"

namespace softdrop {
namespace {

// The contact grid's halo, in cells: a mass's anchor ball (the contact limit) may reach past its
// cell's edge by this much, so a mass moving through open pore space leaves its ball, and is
// tested against its whole cell, less often; a cell lists more discs (bench/README.md, "Constants
// of the step").
constexpr double kContactGridHalo = 0.5;

// p, once p and m are known valid (before the grid is built on m).
const DropletParams& checked(const DropletParams& p, const Medium& m) {
  std::string why;
  if (!p.IsValid(&why)) throw std::invalid_argument(why);
  if (!m.IsValid(&why)) throw std::invalid_argument(why);
  return p;
}

}  // namespace

DropletModel::DropletModel(const DropletParams& p, const Medium& m)
    : params(checked(p, m)), medium(m), context(make_step_context(p)), grid(m, 0, kContactGridHalo) {
  area0 = p.resting_area();
  if (m.image) field = DistanceField::of(m.image);
  obstacles = field ? field->parts() : static_cast<std::int32_t>(m.grains.size());
  // Only masses are tested against grains; a grain narrower than an edge could slip between two.
  // An image's solid parts are held to the same rule: half the larger side of the box of pixels
  // that holds a part (a disc's radius, for a disc drawn in pixels) must be an edge or more.
  const double longest_edge = context.dmax;
  for (std::size_t i = 0; i < m.grains.size(); ++i)
    if (m.grains[i].r < longest_edge)
      throw std::invalid_argument("grain " + std::to_string(i) + " radius " + detail::num(m.grains[i].r) +
                                  " is smaller than the droplet's longest edge " + detail::num(longest_edge) +
                                  ": use more masses, a smaller radius or larger grains");
  for (std::int32_t k = 0; field && k < field->parts(); ++k) {
    const DistanceField::Extent& e = field->extent(k);
    if (std::max(e.width, e.height) < 2 * longest_edge)
      throw std::invalid_argument(
          "image: the solid part at column " + std::to_string(e.i) + ", row " + std::to_string(m.image->ny - 1 - e.j) +
          " (from the top, as in the file) spans only " + detail::num(e.width) + " x " + detail::num(e.height) +
          " length units, less than twice the droplet's longest edge " + detail::num(longest_edge) +
          ", and could slip between two masses: remove such specks from the image, or use a larger pixel size, "
          "more masses or a smaller radius");
  }
  double top = m.height;
  for (const Grain& g : m.grains) top = std::max(top, g.y + g.r);
  start_y = top + p.radius + 0.05 * p.radius;
  clearance_margin = 1e-9 * (m.width + start_y);
}

}  // namespace softdrop
