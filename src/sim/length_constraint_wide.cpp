// The sequential length constraint on many rings at once: with AVX-512 or AVX, rings of one size go
// as lanes of the lane-by-lane layout (lane_layout.hpp), the block step's own constraint
// (lanes::constrain_sequential) on a copy of them, where there are at least fewest_lane_rings();
// otherwise ring by ring. Either way each ring
// gets the corrections, in the order, that apply_length_constraint gives it alone.
#include <algorithm>

#include "lane_layout.hpp"
#include "lane_policy.hpp"
#include "simd_dispatch.hpp"
#include "softdrop/droplet.hpp"
#include "step_test_seam.hpp"

namespace softdrop {

#if defined(SOFTDROP_AVX_DISPATCH)
namespace {
// The `same` rings (all of n masses, same <= lanes::kMaxLanes) as lanes of the block's constraint,
// on a copy laid out lane by lane; corrections[t] gets ring t's.
void constrain_as_lanes(DropletState* const* rings, int same, int iterations, double dmin, double dmax,
                        int* corrections) {
  const int n = rings[0]->size(), registers = (same + 7) / 8;
  double *x[lanes::kMaxLanes], *y[lanes::kMaxLanes];
  int counts[lanes::kMaxLanes];
  for (int t = 0; t < 8 * registers; ++t) {  // a padding lane reads the last ring
    DropletState* ring = rings[std::min(t, same - 1)];
    x[t] = ring->x.data();
    y[t] = ring->y.data();
  }
  const std::size_t size = static_cast<std::size_t>(n) * 8 * registers;
  double* const X = lanes::step_scratch(2 * size);
  double* const Y = X + size;
  lanes::copy_in(x, X, n, registers);
  lanes::copy_in(y, Y, n, registers);
  lanes::constrain_sequential(X, Y, n, registers, iterations, dmin, dmax, counts);
#if defined(SOFTDROP_TEST_HOOKS)
  ++test_seam::lane_constraint_groups();
#endif
  std::fill(x + same, x + 8 * registers, nullptr);  // and is not copied back
  std::fill(y + same, y + 8 * registers, nullptr);
  lanes::copy_out(x, X, n, registers);
  lanes::copy_out(y, Y, n, registers);
  std::copy(counts, counts + same, corrections);
}
}  // namespace
#endif

void apply_length_constraint_interleaved(DropletState* const* rings, int count, double rest_length, double max_strain,
                                         int iterations, int* corrections) {
  int fewest = 0;  // the fewest rings that go as lanes; 0: none do (SSE2 alone, or no vector code)
#if defined(SOFTDROP_AVX_DISPATCH)
  if (const VectorWidth width = constraint_vector_width(); width >= VectorWidth::avx) fewest = fewest_lane_rings(width);
#endif
  for (int r = 0; r < count;) {
    const int n = rings[r]->size();
    int same = 1;  // rings of one size go together, up to three groups of eight lanes
    while (same < lanes::kMaxLanes && r + same < count && rings[r + same]->size() == n) ++same;
#if defined(SOFTDROP_AVX_DISPATCH)
    if (fewest > 0 && same >= fewest) {
      constrain_as_lanes(rings + r, same, iterations, (1 - max_strain) * rest_length, (1 + max_strain) * rest_length,
                         corrections + r);
      r += same;
      continue;
    }
#endif
    for (const int end = r + same; r < end; ++r)
      corrections[r] = apply_length_constraint(rings[r], rest_length, max_strain, iterations);
  }
}

}  // namespace softdrop
