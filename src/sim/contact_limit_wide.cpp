// The contact limit's common cases eight masses at a time (contact_limit_wide.hpp): contact_limit_kernels.inc
// compiled for AVX-512 and for AVX. The two namespace blocks below, alike with those of
// stages_wide.cpp, are how a kernel written once is compiled for each instruction set.

#include "contact_limit_wide.hpp"

#include <cstdint>

#include "lane_simd.hpp"
#include "softdrop/droplet.hpp"

namespace softdrop::lanes {

#if defined(SOFTDROP_AVX_DISPATCH)
namespace x8_avx {
namespace {
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX
#include "contact_limit_kernels.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace
}  // namespace x8_avx

namespace x8_avx512 {
namespace {
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX512
#include "contact_limit_kernels.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace
}  // namespace x8_avx512

void limit_groups(const ContactRecords& r, int first, int groups, double max_depth, double* deepest, unsigned* todo) {
  if (avx512_in_use())
    x8_avx512::limit_groups_k(r, first, groups, max_depth, deepest, todo);
  else
    x8_avx::limit_groups_k(r, first, groups, max_depth, deepest, todo);
}

#endif

}  // namespace softdrop::lanes
