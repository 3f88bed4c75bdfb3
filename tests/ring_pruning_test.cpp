// The ring-ring stages' pruning (ring_contact.cpp): a mass further from the other ring's box than
// the grids' reach and half of it again queries no grid, and a grid lists only the edges near the
// masses that query it. Neither may change a bit: pairs stepped with the pruning and without it
// (every mass querying a grid of every edge, test_seam::ring_pruning) agree at every step, in
// collisions in free fall, across the periodic boundary, and in a medium.
#include <gtest/gtest.h>

#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.hpp"
#include "same_summary.hpp"
#include "sim/ring_contact.hpp"
#include "sim/ring_group_step.hpp"
#include "sim/step_test_seam.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

#if defined(SOFTDROP_TEST_HOOKS)

// Turns the pruning off for its lifetime.
class PruningOff {
 public:
  PruningOff() { test_seam::ring_pruning() = false; }
  ~PruningOff() { test_seam::ring_pruning() = true; }
  PruningOff(const PruningOff&) = delete;
  PruningOff& operator=(const PruningOff&) = delete;
};

// What a pair thrown at each other in an empty box did, step by step: both rings' states, the
// masses in contact and those the limit moved.
struct Collision {
  std::vector<DropletState> a, b;
  std::vector<std::int64_t> contacts;
  std::vector<int> moved;
  std::int64_t grid_edges = 0;  // edges listed in the stages' grids
};

// Ring a at (xa, 40) at speed va and ring b at (xb, 43) at speed vb, along x, for `steps`.
Collision collide(const Medium& box, double xa, double va, double xb, double vb, int steps) {
  const DropletParams p;
  Simulation a(p, box), b(a);
  a.place(xa, 40);
  b.place(xb, 43);
  for (auto [s, v] : {std::pair{&a.mutable_state(), va}, std::pair{&b.mutable_state(), vb}})
    for (int i = 0; i < s->size(); ++i) s->px[i] = s->x[i] - v * p.dt;
  RingContactScratch scratch;
  std::vector<DropletState*> group_rings;
  std::vector<int> corrections;
  Simulation* sims[2] = {&a, &b};
  Collision c;
  const std::int64_t edges_before = test_seam::ring_grid_edges();
  for (int k = 0; k < steps; ++k) {
    RingPair pair{0, 1, &scratch, 0};
    RingGroup rings{sims, 2, &group_rings, &corrections, &pair, 1};
    run_stages(rings);
    c.a.push_back(a.state());
    c.b.push_back(b.state());
    c.contacts.push_back(scratch.contacts);
    c.moved.push_back(pair.moved);
  }
  c.grid_edges = test_seam::ring_grid_edges() - edges_before;
  return c;
}

TEST(RingPruning, CollisionsInFreeFallAreTheSameBitsWithoutThePruning) {
  // Off centre and at two speeds (at the faster the limit works), and once across the periodic
  // boundary of the box, where the second ring's coordinates are a width away from the first's.
  const Medium box = test::empty_medium(500, 500);
  const double d = 2 * DropletParams{}.radius + 4;
  struct Case {
    const char* name;
    double xa, va, xb, vb;
  };
  for (const Case& c : {Case{"slow", -12, 900, -12 + d, -1500}, Case{"fast", -12, 12000, -12 + d, -15000},
                        Case{"across the boundary", 500 - d / 2, 12000, d / 2, -15000}}) {
    SCOPED_TRACE(c.name);
    const Collision pruned = collide(box, c.xa, c.va, c.xb, c.vb, 3000);
    Collision every;
    {
      const PruningOff off;
      every = collide(box, c.xa, c.va, c.xb, c.vb, 3000);
    }
    std::int64_t touching = 0, limited = 0;
    for (std::size_t k = 0; k < pruned.a.size(); ++k) {
      SCOPED_TRACE("step " + std::to_string(k + 1));
      ASSERT_EQ(pruned.a[k].x, every.a[k].x);
      ASSERT_EQ(pruned.a[k].y, every.a[k].y);
      ASSERT_EQ(pruned.a[k].px, every.a[k].px);
      ASSERT_EQ(pruned.a[k].py, every.a[k].py);
      ASSERT_EQ(pruned.b[k].x, every.b[k].x);
      ASSERT_EQ(pruned.b[k].y, every.b[k].y);
      ASSERT_EQ(pruned.b[k].px, every.b[k].px);
      ASSERT_EQ(pruned.b[k].py, every.b[k].py);
      ASSERT_EQ(pruned.contacts[k], every.contacts[k]);
      ASSERT_EQ(pruned.moved[k], every.moved[k]);
      touching += pruned.contacts[k] > 0;
      limited += pruned.moved[k] > 0;
    }
    EXPECT_GT(touching, 20) << "the rings never met";
    if (c.va > 10000) {
      EXPECT_GT(limited, 0) << "the limit never worked";
    }
    // The pruning did prune: the grids listed fewer edges.
    EXPECT_LT(pruned.grid_edges, every.grid_edges);
    std::cout << "  " << c.name << ": steps in contact " << touching << ", with the limit at work " << limited
              << "; edges listed " << pruned.grid_edges << " pruned, " << every.grid_edges << " without\n";
  }
}

TEST(RingPruning, PairsInAMediumAreTheSameBitsWithoutThePruning) {
  // The paper's cited case, phi = 0.79 non-overlapping, the second droplet released close behind
  // the first so that it catches up with it in the pores.
  const Medium medium = test::small_medium_079();
  const DropletParams p;
  const SecondDroplet second = test::close_behind();
  const RunOptions o = test::long_enough();
  std::int64_t contact_steps = 0, pruned_edges = 0, every_edges = 0;
  for (const double x0 : {60.0, 100.0, 150.0}) {
    std::int64_t before = test_seam::ring_grid_edges();
    const TwoDropletSummary pruned = run_two_droplets(p, medium, x0, o, second);
    pruned_edges += test_seam::ring_grid_edges() - before;
    TwoDropletSummary every;
    {
      const PruningOff off;
      before = test_seam::ring_grid_edges();
      every = run_two_droplets(p, medium, x0, o, second);
      every_edges += test_seam::ring_grid_edges() - before;
    }
    test::expect_same_pair(pruned, every, "start x " + std::to_string(x0));
    contact_steps += pruned.contact_steps;
  }
  EXPECT_GT(contact_steps, 100) << "the rings hardly met";
  EXPECT_LT(pruned_edges, every_edges);
  std::cout << "  steps in contact " << contact_steps << "; edges listed " << pruned_edges << " pruned, " << every_edges
            << " without\n";
}

#else
TEST(RingPruning, NeedsTheTestHooks) {
  GTEST_SKIP() << "built without -DSOFTDROP_TEST_HOOKS=ON (scripts/test.sh builds with it)";
}
#endif

}  // namespace
}  // namespace softdrop
