#pragma once
// Non-overlapping grains placed by relaxation: the grains are put down at random, overlapping, and
// then pushed apart pair by pair until every surface gap holds the spacing rule (spacing.hpp).
// Random sequential addition jams near a covered fraction of 0.55 of the grains grown by half the
// gap; relaxation packs them to well past it, so it reaches lower porosities with wider gaps.

#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop::detail {

/// Moves `grains` (radii fixed) until every pair keeps required_distance(a, b, gap) between
/// centres (the nearest periodic image when `periodic`) and every grain lies inside the box in y
/// (and in x when not periodic). Gauss-Seidel over the pairs found on a grid, in a fixed order, so
/// the result depends on the input alone. Returns false if `max_sweeps` passes over the pairs
/// leave some pair too close (the grains are too many for the box at this gap).
bool relax_spacing(std::vector<Grain>& grains, double width, double height, bool periodic, double gap, int max_sweeps);

}  // namespace softdrop::detail
