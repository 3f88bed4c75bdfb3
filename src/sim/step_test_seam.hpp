#pragma once
// The step driver's seam for tests, compiled only with -DSOFTDROP_TEST_HOOKS=ON (the builds of the
// test scripts): a build for users has none of it.
#include <atomic>
#include <cstdint>

#if defined(SOFTDROP_TEST_HOOKS)
namespace softdrop::test_seam {
/// A deliberate fault in the step's driver (step_driver.hpp), which the golden state hashes of every
/// layout must catch (tests/layout_hash_test.cpp). Set it only while no droplet is stepped.
enum class StepMutation {
  none,
  /// The driver runs the viscosity stage before the collisions, in every layout.
  damps_before_collisions,
};
std::atomic<StepMutation>& step_mutation();
/// Groups of rings apply_length_constraint_interleaved has constrained as lanes on this thread: a
/// test that the lanes path runs where the vector width says it does (both paths give the same
/// bits, so nothing else would show that it had been compiled out).
std::int64_t& lane_constraint_groups();
/// Whether the ring-ring stages leave out the masses too far from the other ring to touch it
/// (ring_contact.cpp). Off, every mass queries a grid of every edge, as the stages did without the
/// pruning: a test compares the two. Set it only while no droplet is stepped.
std::atomic<bool>& ring_pruning();
/// Edges the ring-ring stages have listed in their grids on this thread: what the pruning saves.
std::int64_t& ring_grid_edges();
}  // namespace softdrop::test_seam
#endif
