#pragma once
// The q-quantile of sorted values, interpolating linearly between order statistics (numpy's
// default, "linear": h = (n - 1) q), so that a value we report is the one pandas computes.
#include <algorithm>
#include <cmath>
#include <vector>

namespace softdrop::detail {

inline double linear_quantile(const std::vector<double>& sorted, double q) {
  const double h = static_cast<double>(sorted.size() - 1) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

}  // namespace softdrop::detail
