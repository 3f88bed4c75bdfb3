#pragma once
/// \file averaging.hpp
/// The paper's two ways of averaging the same per-medium points (phi, <T>): sort them by T
/// (type 1) or by phi (type 2), cut the sorted list into consecutive groups of n points, and
/// average phi and T within each group. The points left over after the last full group are
/// dropped (the paper's groups are all of n points) or averaged as a last, smaller group.

#include <vector>

namespace softdrop {

/// One medium's point.
struct MediumPoint {
  double phi = 0, t = 0;
};

/// A group's averages and the standard errors of those averages.
struct GroupAverage {
  double phi = 0, t = 0, phi_se = 0, t_se = 0;
  int count = 0;
};

enum class AveragingType {
  by_t = 1,   ///< type 1: sorted by T
  by_phi = 2  ///< type 2: sorted by phi
};

/// What becomes of the points left over after the last full group: the highest in T (type 1) or
/// in phi (type 2), so dropping them trims that end of the curve.
enum class Leftover {
  drop,  ///< left out: every group has `group` points, as the paper's
  keep   ///< averaged as a last group of fewer points (its count says how many)
};

/// Groups of `group` points (group >= 1); ties are broken by the other coordinate, so the result
/// does not depend on the input order.
std::vector<GroupAverage> group_averages(std::vector<MediumPoint> points, AveragingType type, int group,
                                         Leftover leftover = Leftover::drop);

}  // namespace softdrop
