#pragma once
/// \file porosity.hpp
/// Void fraction of a medium's box: exact (analytic area of the union of discs) and Monte Carlo.

#include <cstdint>

#include "softdrop/medium.hpp"

namespace softdrop {

/// Exact porosity: 1 - area(union of grains, clipped to the box) / (W H), periodic in x when the
/// medium is. Computed with Green's theorem over the uncovered circle arcs and covered box edges.
double exact_porosity(const Medium& medium);

/// Area of the union of the grains clipped to the box (length units squared).
double solid_area(const Medium& medium);

/// Monte Carlo estimate of the porosity from `samples` uniform points and its standard error.
struct PorosityEstimate {
  double porosity = 0;
  double standard_error = 0;
};
PorosityEstimate monte_carlo_porosity(const Medium& medium, std::int64_t samples, std::uint64_t seed);

}  // namespace softdrop
