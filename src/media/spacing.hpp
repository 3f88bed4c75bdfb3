#pragma once
/// \file spacing.hpp
/// The spacing rule of non-overlapping media, enforced with CGAL: the surface gap between any two
/// grains is at least `gap` times the larger of their two radii (periodic in x when the medium is),
/// and every grain lies inside the box in y.

#include <memory>
#include <optional>
#include <utility>

#include "softdrop/medium.hpp"

namespace softdrop {

/// Minimum centre distance that two grains of radii a and b need: a + b + gap * max(a, b).
double required_distance(double a, double b, double gap);

/// A growing set of grains that answers "may a grain of radius r go at (x, y)?" in O(log n) on
/// average, backed by a CGAL Delaunay triangulation and its circular range search.
class SpacingIndex {
 public:
  SpacingIndex(double width, double height, bool periodic, double gap, double r_max);
  ~SpacingIndex();
  SpacingIndex(SpacingIndex&&) noexcept;
  SpacingIndex& operator=(SpacingIndex&&) noexcept;

  /// True if the grain keeps the gap to every grain inserted so far and lies inside the box in y.
  /// Its radius must not exceed the r_max given at construction.
  bool can_place(const Grain& g) const;
  /// Adds a grain (no check; call can_place first). Its id is the number of grains before it.
  void insert(const Grain& g);
  /// True if grain `i` may be replaced by `g`: the rule of can_place against every other grain.
  /// Throws std::out_of_range for a bad id.
  bool can_move(int i, const Grain& g) const;
  /// Replaces grain `i` by `g` (no check; call can_move first).
  void move(int i, const Grain& g);
  /// Grain `i` as stored.
  const Grain& grain(int i) const;
  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The first pair (i, j) that breaks the spacing rule, or the pair (i, i) for a grain outside the
/// box in y; nullopt if the medium satisfies it.
std::optional<std::pair<int, int>> find_spacing_violation(const Medium& medium, double gap);

}  // namespace softdrop
