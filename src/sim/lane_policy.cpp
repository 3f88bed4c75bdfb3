#include "lane_policy.hpp"

#include <algorithm>

#include "lane_layout.hpp"

namespace softdrop {

int interleaved_lanes() { return constraint_vector_width() >= VectorWidth::avx ? lanes::kMaxLanes : 1; }

int batch_lanes(int requested) { return requested == 0 ? interleaved_lanes() : requested; }

std::size_t fewest_block_droplets() { return 3; }

int fewest_lane_rings(VectorWidth width) { return width == VectorWidth::avx512 ? 3 : 4; }

int speculative_lanes(int per_generation, int threads, ConstraintOrder order) {
  const VectorWidth width = constraint_vector_width();
  if (width < VectorWidth::avx) return 1;  // one at a time: more lanes would only run further ahead
  if (order == ConstraintOrder::red_black && width == VectorWidth::avx && per_generation == 1 && threads > 1) return 1;
  constexpr int kPerThread = 8;
  return std::max(1, std::min(kPerThread, 2 * kPerThread / threads));
}

}  // namespace softdrop
