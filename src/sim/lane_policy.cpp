#include "lane_policy.hpp"

#include <algorithm>

#include "lane_layout.hpp"

namespace softdrop {

int interleaved_ring_capacity() {
  const VectorWidth width = constraint_vector_width();
  return width >= VectorWidth::avx512 ? 24 : width >= VectorWidth::avx ? 12 : width >= VectorWidth::sse2 ? 6 : 1;
}

int interleaved_lanes() {
  return constraint_vector_width() >= VectorWidth::avx ? lanes::kMaxLanes : interleaved_ring_capacity();
}

int batch_lanes(int requested) { return requested == 0 ? interleaved_lanes() : requested; }

std::size_t fewest_block_droplets(VectorWidth width) { return width == VectorWidth::avx512 ? 3 : 6; }

int speculative_lanes(int per_generation, int threads, ConstraintOrder order) {
  const VectorWidth width = constraint_vector_width();
  if (order == ConstraintOrder::red_black &&
      (width < VectorWidth::avx || (width == VectorWidth::avx && per_generation == 1 && threads > 1)))
    return 1;
  const int per_thread = width >= VectorWidth::avx ? 8 : std::min(8, 4 * per_generation);
  return std::max(1, std::min(per_thread, 2 * per_thread / threads));
}

}  // namespace softdrop
