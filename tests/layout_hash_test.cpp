// Every layout of the step keeps the golden state hashes (golden_hashes.hpp): one ring stepped
// alone or run by its run loop, rings stepped one after another with their constraints together, and
// droplets laid out lane by lane in a block, at every vector width the processor has. A driver that
// drifts from the others by one rounding fails here, even where the droplets' summaries agree. The
// run loops end as the droplet leaves the medium, so they are held to the state there (run_hash).
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <sstream>
#include <string>
#include <vector>

#include "fixtures.hpp"
#include "golden_hashes.hpp"
#include "sim/interleaved.hpp"
#include "sim/lane_policy.hpp"
#include "sim/ring_group_step.hpp"
#include "sim/step_test_seam.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

std::string hex(std::uint64_t h) {
  std::ostringstream s;
  s << "0x" << std::hex << h;
  return s.str();
}

// Run options with no stuck or rest test within `steps` steps: a golden droplet passes first.
RunOptions exactly(int steps) {
  RunOptions o;
  o.max_steps = steps;
  o.stuck_window = 1e6;
  o.rest_window = 0;
  return o;
}

struct RunEnd {
  std::uint64_t hash = 0;
  std::int64_t steps = 0;
  Outcome outcome = Outcome::timeout;
};

// How each droplet of `runs` ends its run, all stepped together by run_interleaved on one thread
// with a lane for each (with AVX or AVX-512, enough droplets of the first one's parameters go as a
// lane-by-lane block, the others ring by ring).
std::vector<RunEnd> interleaved_ends(const std::vector<test::GoldenRun>& runs) {
  const Medium pore = test::pore_of_three_grains();
  std::deque<Simulation> sims;
  std::vector<RunOptions> options;
  for (const test::GoldenRun& g : runs) {
    sims.emplace_back(g.params, pore);
    options.push_back(exactly(g.steps));
  }
  std::vector<RunEnd> ends(runs.size());
  std::size_t handed = 0;
  run_interleaved(
      static_cast<int>(runs.size()),
      [&](DropletJob* job, bool) {
        if (handed == runs.size()) return false;
        *job = DropletJob{&sims[handed], 100, &options[handed], static_cast<std::int64_t>(handed)};
        ++handed;
        return true;
      },
      [&](std::int64_t id, RunSummary&& s) {
        RunEnd& end = ends[static_cast<std::size_t>(id)];
        end.steps = s.steps;
        end.outcome = s.outcome;
      });
  for (std::size_t d = 0; d < runs.size(); ++d) ends[d].hash = sims[d].state_hash();
  return ends;
}

// Four droplets of golden run `g` stepped `g.steps` times as a ring group (RingGroup, the layout
// run_interleaved steps the droplets outside a block in): their states' hashes. With AVX or
// AVX-512 their sequential constraints go as lanes of the block's constraint (four rings, at
// least fewest_lane_rings(), padded to a group of eight); otherwise one after another.
std::vector<std::uint64_t> ring_group_hashes(const test::GoldenRun& g, const Medium& medium) {
  std::deque<Simulation> sims;
  std::vector<Simulation*> group_sims;
  for (int t = 0; t < 4; ++t) {
    sims.emplace_back(g.params, medium);
    sims.back().place_above(100);
    group_sims.push_back(&sims.back());
  }
  std::vector<DropletState*> rings;
  std::vector<int> corrections;
  RingGroup group{group_sims.data(), static_cast<int>(group_sims.size()), &rings, &corrections};
  for (int k = 0; k < g.steps; ++k) run_stages(group);
  std::vector<std::uint64_t> hashes;
  for (const Simulation& sim : sims) hashes.push_back(sim.state_hash());
  return hashes;
}

// Each droplet ended as its golden run's run loop ends.
void expect_golden_ends(const std::vector<test::GoldenRun>& runs, const std::vector<RunEnd>& ends) {
  for (std::size_t d = 0; d < runs.size(); ++d) {
    SCOPED_TRACE("run_interleaved, droplet " + std::to_string(d) + " (" + runs[d].name + ")");
    EXPECT_EQ(ends[d].outcome, Outcome::passed);
    EXPECT_EQ(ends[d].steps, runs[d].run_steps);
    EXPECT_EQ(hex(ends[d].hash), hex(runs[d].run_hash));
  }
}

// Nine droplets of golden run `g` (a block of two groups with AVX-512, padding lanes included) and
// one of the next golden run beside them (stepped ring by ring, in the same steps).
std::vector<test::GoldenRun> nine_and_one(const std::vector<test::GoldenRun>& golden, std::size_t g) {
  std::vector<test::GoldenRun> runs(9, golden[g]);
  runs.push_back(golden[(g + 1) % golden.size()]);
  return runs;
}

TEST(LayoutHash, EveryLayoutAtEveryWidthKeepsTheGoldenHashes) {
  const std::vector<test::GoldenRun> golden = test::golden_runs();
  const Medium pore = test::pore_of_three_grains();
  test::LackedWidths lacked;
  for (VectorWidth width : test::kVectorWidths) {
    const test::VectorWidthLimit limit(width);
    if (!lacked.has(limit, width)) continue;
    for (std::size_t g = 0; g < golden.size(); ++g) {
      SCOPED_TRACE(golden[g].name + ", vector width " + std::to_string(static_cast<int>(width)));
      // One ring, step by step (to the golden step, and to the step its run ends at), then
      // through its run loop.
      Simulation sim(golden[g].params, pore);
      sim.place_above(100);
      for (int k = 0; k < golden[g].steps; ++k) {
        sim.step();
        if (k + 1 == golden[g].run_steps) {
          EXPECT_EQ(hex(sim.state_hash()), hex(golden[g].run_hash)) << "step, run end";
        }
      }
      EXPECT_EQ(hex(sim.state_hash()), hex(golden[g].hash)) << "Simulation::step";
      const RunSummary run = sim.run(100, exactly(golden[g].steps));
      EXPECT_EQ(run.outcome, Outcome::passed) << run.reason;
      EXPECT_EQ(run.steps, golden[g].run_steps);
      EXPECT_EQ(hex(sim.state_hash()), hex(golden[g].run_hash)) << "Simulation::run";
      // A ring group of four.
      for (const std::uint64_t h : ring_group_hashes(golden[g], pore))
        EXPECT_EQ(hex(h), hex(golden[g].hash)) << "RingGroup";
      // Side by side: a block (AVX, AVX-512) or a ring group (SSE2, scalar), and a ring of other
      // parameters stepped with them.
      const std::vector<test::GoldenRun> runs = nine_and_one(golden, g);
      expect_golden_ends(runs, interleaved_ends(runs));
    }
  }
  if (lacked.any()) GTEST_SKIP() << lacked.message();
}

TEST(LayoutHash, ADriftingDriverFailsTheGoldenHashesInEveryLayout) {
  // The one driver runs the viscosity stage before the collisions: every layout runs the drifted
  // order, and every droplet of each loses its golden hash; cleared, the hashes come back. The
  // droplets take the implicit viscosity step, whose damping reads the forces of the stages before
  // it (with the other steps the drift only reorders two additions, which these scenes' bits do
  // not show). A change far below a position's rounding, such as a constant one unit in the last
  // place off, leaves every bit of these scenes too: Verlet's step rounds it away.
#if defined(SOFTDROP_TEST_HOOKS)
  const test::GoldenRun defaults = test::golden_runs()[0];
  ASSERT_EQ(defaults.params.viscosity_step, ViscosityStep::implicit);
  const Medium pore = test::pore_of_three_grains();
  // Nine droplets of the defaults (a block with AVX or AVX-512) and, beside them, one of other
  // parameters, which no block takes (ring by ring at every width).
  std::vector<test::GoldenRun> runs(9, defaults);
  runs.push_back(defaults);
  runs.back().params.viscosity = 1.2e5;
  test::LackedWidths lacked;
  for (VectorWidth width : test::kVectorWidths) {
    const test::VectorWidthLimit limit(width);
    if (!lacked.has(limit, width)) continue;
    SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(width)));
    const std::vector<RunEnd> clean = interleaved_ends(runs);
    test_seam::step_mutation() = test_seam::StepMutation::damps_before_collisions;
    Simulation sim(defaults.params, pore);
    sim.place_above(100);
    for (int k = 0; k < defaults.steps; ++k) sim.step();
    const std::uint64_t stepped = sim.state_hash();
    const std::vector<RunEnd> mutated = interleaved_ends(runs);
    const std::vector<std::uint64_t> group = ring_group_hashes(defaults, pore);
    test_seam::step_mutation() = test_seam::StepMutation::none;
    EXPECT_NE(hex(stepped), hex(defaults.hash)) << "Simulation::step";
    for (const std::uint64_t h : group) EXPECT_NE(hex(h), hex(defaults.hash)) << "RingGroup";
    for (std::size_t d = 0; d < runs.size(); ++d)
      EXPECT_NE(hex(mutated[d].hash), hex(clean[d].hash)) << "run_interleaved, droplet " << d;
    const std::vector<test::GoldenRun> nine(runs.begin(), runs.begin() + 9);
    expect_golden_ends(nine, std::vector<RunEnd>(clean.begin(), clean.begin() + 9));
  }
  if (lacked.any()) GTEST_SKIP() << lacked.message();
#else
  GTEST_SKIP() << "built without -DSOFTDROP_TEST_HOOKS=ON (scripts/test.sh builds with it)";
#endif
}

}  // namespace
}  // namespace softdrop
