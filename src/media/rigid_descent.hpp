#pragma once
/// \file rigid_descent.hpp
/// The geometric limit of gravity-driven passage: a rigid, frictionless disc without inertia, moved
/// by gravity alone through a medium. It falls straight down, slides along the upper half of the
/// grain it lands on to the grain's widest point, falls again, and stops where no direction open to
/// it descends: a dead end between two grains, or between a grain and a side wall. The geometry is
/// exact (circles), on the grains dilated by the disc's radius.
///
/// A droplet that neither deforms nor bounces passes exactly where this disc passes, so the
/// fraction of starts it passes bounds what the medium's dead ends allow; a soft droplet may pass
/// more (it squeezes through gaps narrower than itself, and its inertia carries it over small lips)
/// or less (it may stop on a ledge before reaching a dead end).

#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop {

/// Where one rigid descent ended.
struct RigidDescent {
  bool passed = false;    ///< the centre went below y = 0; otherwise it stopped in a dead end
  double tortuosity = 0;  ///< path length between y = H and y = 0 over H (passed only, else NaN)
  double x = 0;           ///< where the centre crossed y = 0 (passed) or stopped (length units)
  double y = 0;           ///< 0 when passed, the stopping height otherwise
  int slides = 0;         ///< grain surfaces it slid along
  /// The centre's path, if asked: from the start above the medium to the end, arcs sampled every
  /// 0.02 rad; x does not jump at the periodic edge (it runs on past W or below 0).
  std::vector<double> path_x, path_y;
};

/// Drops a rigid disc of `radius` (length units, >= 0; 0 is a point) with its centre at x0 (in
/// [0, W]) from above the medium. With side walls the centre is kept at least `radius` from each
/// wall (x0 is moved in if need be). Deterministic: the same inputs give the same bits. Throws
/// std::invalid_argument naming radius or x0 if it is negative, non-finite, out of the box, or the
/// disc is wider than the box (periodic: its diameter must be < width, as a grain's).
RigidDescent rigid_descent(const Medium& medium, double radius, double x0, bool record_path = false);

/// rigid_descent for each start in `x0s`, in order (every start is checked first).
std::vector<RigidDescent> rigid_descents(const Medium& medium, double radius, const std::vector<double>& x0s,
                                         bool record_paths = false);

}  // namespace softdrop
