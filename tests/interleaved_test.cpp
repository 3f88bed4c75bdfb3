// Droplets stepped together (run_interleaved, apply_length_constraint_interleaved) must get exactly
// the numbers they get alone: the interleaving only lets the processor overlap independent chains.
#include "sim/interleaved.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <latch>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "fixtures.hpp"
#include "same_summary.hpp"
#include "sim/lane_layout.hpp"
#include "sim/lane_policy.hpp"
#include "sim/step_test_seam.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

void expect_same(const RunSummary& a, const RunSummary& b, const std::string& what) {
  test::expect_same_summary(a, b, what);
}

// A generated overlapping medium, 200 x 200 at porosity 0.8: droplets pass, get stuck and run for
// very different numbers of steps.
Medium medium_of_porosity_08() {
  MediumOptions mo;
  mo.porosity = 0.8;
  mo.width = mo.height = 200;
  mo.r_min = test::kBalloonRMin, mo.r_max = test::kBalloonRMax;  // (many grains in a small box)
  mo.seed = 3;
  return generate_medium(mo);
}

TEST(Interleaved, RingsConstrainedTogetherEndAsEachAlone) {
  // Rings of mixed sizes, stretched and squeezed at random, at every vector width. With AVX-512 or
  // AVX, rings of one size go as lanes of the block's constraint, up to 24 at a time (the 26
  // first: 24, then 2), the five last in one group of eight with three padding lanes; groups under
  // fewest_lane_rings (2 and 2 rings, 1) go one by one, as they all do with SSE2 or none.
  std::vector<int> sizes(26, 40);
  for (int masses : {41, 41, 16, 40, 40, 40, 40, 40}) sizes.push_back(masses);
  const DropletParams p;
  for (VectorWidth width : test::kVectorWidths) {
    const test::VectorWidthLimit limit(width);
    SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(limit.in_use())));
    std::vector<DropletState> alone, together;
    for (int masses : sizes) {
      alone.push_back(test::jiggled_ring(masses, alone.size() + 7, 0.5));
      together.push_back(alone.back());
    }
    std::vector<DropletState*> rings;
    for (auto& s : together) rings.push_back(&s);
    std::vector<int> corrections(rings.size());
    // The same rest length for all, as run_interleaved groups them; 3 passes, some rings converge first.
#if defined(SOFTDROP_TEST_HOOKS)
    const std::int64_t groups_before = test_seam::lane_constraint_groups();
#endif
    apply_length_constraint_interleaved(rings.data(), static_cast<int>(rings.size()), p.rest_length(), p.max_strain, 3,
                                        corrections.data());
#if defined(SOFTDROP_TEST_HOOKS)
    // Two groups as lanes (24 rings, then the five last) with AVX-512 or AVX, none otherwise.
    EXPECT_EQ(test_seam::lane_constraint_groups() - groups_before, limit.in_use() >= VectorWidth::avx ? 2 : 0);
#endif
    for (std::size_t r = 0; r < alone.size(); ++r) {
      const int c = apply_length_constraint(&alone[r], p.rest_length(), p.max_strain, 3);
      EXPECT_EQ(corrections[r], c) << "ring " << r;
      EXPECT_EQ(together[r].x, alone[r].x) << "ring " << r;
      EXPECT_EQ(together[r].y, alone[r].y) << "ring " << r;
    }
  }
}

TEST(Interleaved, LaneKernelsConstrainEachRingAsAlone) {
  // The lane-by-lane constraint (lanes::constrain_sequential, constrain_red_black) straight on the
  // layout, with AVX-512 and AVX, in 1 to 3 groups of eight. In each group some rings are in limits
  // from the start (one pass, no correction) while the others change in every pass, in the low
  // half of one group, the high half of another, every other lane of the third: a group's passes
  // must go on while any of its rings changes. Each ring and its corrections must be those of
  // apply_length_constraint alone; the copy out can move what the rings held to other arrays.
  const int n = 40, iterations = 4;
  const DropletParams p = [] {  // rings of 40 masses, as jiggled_ring places them
    DropletParams d;
    d.masses = n;
    return d;
  }();
  const double dmax = (1 + p.max_strain) * p.rest_length(), dmin = (1 - p.max_strain) * p.rest_length();
  test::LackedWidths lacked;
  for (VectorWidth width : {VectorWidth::avx, VectorWidth::avx512}) {
    const test::VectorWidthLimit limit(width);
    if (!lacked.has(limit, width)) continue;
    for (ConstraintOrder order : {ConstraintOrder::sequential, ConstraintOrder::red_black}) {
      for (int registers = 1; registers <= lanes::kMaxLaneRegisters; ++registers) {
        SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(width)) + ", " + to_string(order) + ", " +
                     std::to_string(registers) + " groups");
        const int L = 8 * registers;
        std::vector<DropletState> rings, alone;
        std::vector<double*> xs, ys;
        std::vector<bool> calm;
        for (int t = 0; t < L; ++t) {
          const int g = t / 8, b = t % 8;
          calm.push_back(g == 0 ? b < 4 : g == 1 ? b >= 4 : b % 2 == 0);
          DropletState s = test::jiggled_ring(n, 100 + static_cast<std::uint64_t>(t), calm.back() ? 0.0 : 0.5);
          if (calm.back())  // springs 0.97 of the inflated ring's: inside the limits
            for (int i = 0; i < n; ++i) s.x[i] = 3 + 0.97 * (s.x[i] - 3), s.y[i] = 4 + 0.97 * (s.y[i] - 4);
          rings.push_back(s);
          alone.push_back(s);
        }
        for (DropletState& s : rings) xs.push_back(s.x.data()), ys.push_back(s.y.data());
        std::vector<double> X(static_cast<std::size_t>(n * L)), Y(X.size());
        lanes::copy_in(xs.data(), X.data(), n, registers);
        lanes::copy_in(ys.data(), Y.data(), n, registers);
        std::vector<int> counts(static_cast<std::size_t>(L), -1);
        if (order == ConstraintOrder::sequential)
          lanes::constrain_sequential(X.data(), Y.data(), n, registers, iterations, dmin, dmax, counts.data());
        else
          lanes::constrain_red_black(X.data(), Y.data(), n, registers, iterations, dmin, dmax, counts.data());
        // x goes out moving what the rings held to px (as the block step does), y plainly.
        std::vector<double*> pxs;
        for (DropletState& s : rings) pxs.push_back(s.px.data());
        const std::vector<DropletState> before = rings;
        lanes::copy_out(xs.data(), X.data(), n, registers, pxs.data());
        lanes::copy_out(ys.data(), Y.data(), n, registers);
        for (int t = 0; t < L; ++t) {
          EXPECT_EQ(rings[static_cast<std::size_t>(t)].px, before[static_cast<std::size_t>(t)].x) << "ring " << t;
          EXPECT_EQ(rings[static_cast<std::size_t>(t)].py, before[static_cast<std::size_t>(t)].py) << "ring " << t;
          const int c = apply_length_constraint(&alone[static_cast<std::size_t>(t)], p.rest_length(), p.max_strain,
                                                iterations, order);
          EXPECT_EQ(calm[static_cast<std::size_t>(t)], c == 0) << "ring " << t;
          EXPECT_EQ(counts[static_cast<std::size_t>(t)], c) << "ring " << t;
          EXPECT_EQ(rings[static_cast<std::size_t>(t)].x, alone[static_cast<std::size_t>(t)].x) << "ring " << t;
          EXPECT_EQ(rings[static_cast<std::size_t>(t)].y, alone[static_cast<std::size_t>(t)].y) << "ring " << t;
        }
      }
    }
  }
  if (lacked.any()) GTEST_SKIP() << lacked.message();
}

TEST(Interleaved, EveryDropletHasTheBitsOfItsSoloRun) {
  // Mixed lanes: the defaults and the balloon (whose springs sit at their limit), the reference
  // order, a red-black droplet (constrained on its own), another ring size; recordings on;
  // droplets of very different lengths, so lanes are refilled mid-run.
  const Medium medium = medium_of_porosity_08();
  const Medium pore = test::pore_of_three_grains();
  RunOptions o;
  o.stuck_window = 0.1;
  o.path_interval = 50;
  o.area_interval = 100;
  o.snapshot_times = {0.001, 0.01};
  struct Case {
    DropletParams p;
    const Medium* m;
    double x0;
  };
  std::vector<Case> cases;
  for (int i = 0; i < 9; ++i) {
    DropletParams p = i % 2 == 1 ? test::balloon_droplet() : DropletParams{};
    if (i % 4 == 1) p.constraint_order = ConstraintOrder::red_black;
    if (i % 3 == 2) p.masses = 32;
    if (i == 2 || i == 5) {  // a shaken medium, from the start and from rest, along y and xy
      p.vibration_amplitude = 1.5, p.vibration_frequency = 400;
      p.vibration_axis = i == 2 ? VibrationAxis::y : VibrationAxis::xy;
      p.vibration_start = i == 2 ? VibrationStart::start : VibrationStart::rest;
    }
    cases.push_back({p, i % 5 == 4 ? &pore : &medium, 20.0 + 19.0 * i});
  }
  std::vector<RunSummary> solo;
  for (const Case& c : cases) solo.push_back(Simulation(c.p, *c.m).run(c.x0, o));
  for (int lanes : {1, 2, 3, 5, 7}) {
    std::vector<std::unique_ptr<Simulation>> sims;
    for (const Case& c : cases) sims.push_back(std::make_unique<Simulation>(c.p, *c.m));
    std::size_t next = 0;
    std::map<std::int64_t, RunSummary> got;
    run_interleaved(
        lanes,
        [&](DropletJob* job, bool) {
          if (next == cases.size()) return false;
          *job = {sims[next].get(), cases[next].x0, &o, static_cast<std::int64_t>(next)};
          ++next;
          return true;
        },
        [&](std::int64_t id, RunSummary&& s) { got.emplace(id, std::move(s)); });
    ASSERT_EQ(got.size(), cases.size()) << lanes << " lanes";
    for (std::size_t i = 0; i < cases.size(); ++i)
      expect_same(got.at(static_cast<std::int64_t>(i)), solo[i],
                  "droplet " + std::to_string(i) + ", " + std::to_string(lanes) + " lanes");
  }
  int outcomes[4] = {};
  for (const RunSummary& s : solo) ++outcomes[static_cast<int>(s.outcome)];
  EXPECT_GT(outcomes[static_cast<int>(Outcome::passed)], 0);
  EXPECT_GT(outcomes[static_cast<int>(Outcome::stuck)], 0);
}

TEST(Interleaved, DropletsSteppedLaneByLaneHaveTheBitsOfTheirSoloRuns) {
  // 30 lanes: with AVX-512 or AVX the droplets of the first one's parameters go lane by lane
  // (blocks of up to 24: three groups of eight, then one with padding lanes), the others (other stiffness, the other
  // constraint order, another ring size) droplet by droplet. Solid walls, droplets started against
  // them; with and without viscosity, either order first, an even and an odd ring. Each must end as
  // it does alone, at every vector width.
  MediumOptions mo;
  mo.porosity = 0.8;
  mo.width = mo.height = 200;
  mo.seed = 11;
  mo.periodic = false;
  const Medium medium = generate_medium(mo);
  RunOptions o;
  o.stuck_window = 0.1;
  o.max_steps = 15000;
  o.path_interval = 40;
  const ConstraintOrder seq = ConstraintOrder::sequential, rb = ConstraintOrder::red_black;
  // An odd ring (41 masses) too: red-black's closing spring then touches the first spring's mass;
  // a viscosity that spares the ring's dilation; the exponential and the implicit viscosity steps
  // (the implicit one reads the other stages' forces, so their order and sums must agree too).
  const ViscosityStep ex = ViscosityStep::explicit_euler;
  for (auto [viscosity, order, masses, dilation, step] :
       {std::tuple{1.0e4, seq, 40, 1.0, ex}, std::tuple{0.0, seq, 40, 1.0, ex}, std::tuple{1.0e4, rb, 40, 1.0, ex},
        std::tuple{1.0e4, rb, 41, 1.0, ex}, std::tuple{1.0e4, seq, 40, 0.0, ex},
        std::tuple{1.0e5, seq, 40, 0.0, ViscosityStep::exponential},
        std::tuple{1.37e5, seq, 40, 0.0, ViscosityStep::implicit},
        std::tuple{1.37e5, rb, 41, 1.0, ViscosityStep::implicit}}) {
    SCOPED_TRACE("viscosity " + std::to_string(viscosity) + ", " + to_string(order) + ", " + std::to_string(masses) +
                 " masses, dilation share " + std::to_string(dilation) + ", " + to_string(step) + " step");
    std::vector<DropletParams> params;
    std::vector<double> x0;
    for (int i = 0; i < 30; ++i) {
      DropletParams p;
      p.viscosity = viscosity;
      p.viscosity_dilation = dilation;
      p.constraint_order = order;
      p.masses = masses;
      p.viscosity_step = step;
      if (i % 7 == 3) p.ks *= 1.1;
      if (i % 11 == 5) p.constraint_order = order == seq ? rb : seq;
      if (i % 13 == 6) p.masses = 32;
      if (i % 5 == 2) {  // shaken droplets beside unshaken ones in a block (-0 in their lanes)
        p.vibration_amplitude = 1.0 + 0.25 * (i % 3), p.vibration_frequency = 250 + 10 * i;
        p.vibration_axis = i % 3 == 0 ? VibrationAxis::x : i % 3 == 1 ? VibrationAxis::y : VibrationAxis::xy;
        p.vibration_start = i % 2 == 0 ? VibrationStart::start : VibrationStart::rest;
      }
      params.push_back(p);
      x0.push_back(i % 10 == 0 ? 4.0 : i % 10 == 9 ? 196.0 : 6.0 + 6.3 * i);
    }
    std::vector<RunSummary> solo;
    std::vector<std::uint64_t> solo_end;  // the state each run ends in
    for (std::size_t i = 0; i < params.size(); ++i) {
      Simulation alone(params[i], medium);
      solo.push_back(alone.run(x0[i], o));
      solo_end.push_back(alone.state_hash());
    }
    for (VectorWidth width : test::kVectorWidths) {
      const test::VectorWidthLimit limit(width);
      SCOPED_TRACE("vector width " + std::to_string(static_cast<int>(limit.in_use())));
      std::vector<std::unique_ptr<Simulation>> sims;
      for (const DropletParams& p : params) sims.push_back(std::make_unique<Simulation>(p, medium));
      std::size_t next = 0;
      std::map<std::int64_t, RunSummary> got;
      run_interleaved(
          30,
          [&](DropletJob* job, bool) {
            if (next == params.size()) return false;
            *job = {sims[next].get(), x0[next], &o, static_cast<std::int64_t>(next)};
            ++next;
            return true;
          },
          [&](std::int64_t id, RunSummary&& s) { got.emplace(id, std::move(s)); });
      ASSERT_EQ(got.size(), params.size());
      for (std::size_t i = 0; i < params.size(); ++i)
        expect_same(got.at(static_cast<std::int64_t>(i)), solo[i], "droplet " + std::to_string(i));
      for (std::size_t i = 0; i < params.size(); ++i) EXPECT_EQ(sims[i]->state_hash(), solo_end[i]) << "droplet " << i;
    }
    int walls = 0, outcomes[4] = {};
    for (const RunSummary& s : solo) {
      ++outcomes[static_cast<int>(s.outcome)];
      walls += s.start_x < 10 || s.start_x > 190;
    }
    EXPECT_GT(outcomes[static_cast<int>(Outcome::passed)], 0);
    EXPECT_GT(outcomes[static_cast<int>(Outcome::stuck)] + outcomes[static_cast<int>(Outcome::timeout)], 0);
    EXPECT_EQ(walls, 6);
  }
}

TEST(Interleaved, BatchResultsDoNotDependOnLanesOrThreads) {
  MediumOptions mo;
  mo.porosity = 0.75;
  mo.seed = 5;
  const Medium m = generate_medium(mo);
  DropletParams p;
  RunOptions o;
  o.stuck_window = 0.2;
  BatchOptions b;
  b.droplets = 10;
  b.threads = 1;
  b.lanes = 1;
  const auto reference = run_batch(p, m, o, b);
  for (auto [threads, lanes] : {std::pair{1, 3}, std::pair{2, 6}, std::pair{2, 4}, std::pair{1, 10}}) {
    b.threads = threads;
    b.lanes = lanes;
    const auto runs = run_batch(p, m, o, b);
    ASSERT_EQ(runs.size(), reference.size());
    for (std::size_t i = 0; i < runs.size(); ++i)
      expect_same(runs[i], reference[i],
                  "droplet " + std::to_string(i) + ", " + std::to_string(threads) + " threads, " +
                      std::to_string(lanes) + " lanes");
  }
  b.lanes = 0;  // chosen for the processor: the same bits again
  const auto chosen = run_batch(p, m, o, b);
  ASSERT_EQ(chosen.size(), reference.size());
  for (std::size_t i = 0; i < chosen.size(); ++i) expect_same(chosen[i], reference[i], "lanes chosen");
  for (int lanes : {-1, 65}) {
    b.lanes = lanes;
    EXPECT_THROW(run_batch(p, m, o, b), std::invalid_argument) << lanes << " lanes";
  }
  EXPECT_THROW(limit_constraint_vector_width(static_cast<VectorWidth>(3)), std::invalid_argument);
}

TEST(Interleaved, DropletsHandedToAnIdleThreadKeepTheirBits) {
  // Thread A has all 8 droplets and steps 6 at a time; thread B joins once A is stepping, has none
  // of its own, so it waits at the exchange and A hands it running droplets. Every droplet still
  // gets its solo bits.
  const Medium medium = medium_of_porosity_08();
  const DropletParams p;
  RunOptions o;
  o.stuck_window = 0.1;
  o.path_interval = 50;
  constexpr int kDroplets = 8;
  std::vector<RunSummary> solo;
  std::vector<std::unique_ptr<Simulation>> sims;
  for (int i = 0; i < kDroplets; ++i) {
    solo.push_back(Simulation(p, medium).run(15.0 + 23.0 * i, o));
    sims.push_back(std::make_unique<Simulation>(p, medium));
  }
  LaneExchange exchange;
  std::mutex m;
  std::map<std::int64_t, RunSummary> got;
  int finished_by_b = 0;
  std::latch a_is_stepping(1);
  std::once_flag once;
  RunOptions oa = o;  // asked every check_interval steps; says A has stepped
  oa.cancelled = [&] {
    std::call_once(once, [&] { a_is_stepping.count_down(); });
    return false;
  };
  std::thread a([&] {
    int next = 0;
    run_interleaved(
        6,
        [&](DropletJob* job, bool) {
          if (next == kDroplets) return false;
          *job = {sims[static_cast<std::size_t>(next)].get(), 15.0 + 23.0 * next, &oa, next};
          ++next;
          return true;
        },
        [&](std::int64_t id, RunSummary&& s) {
          std::lock_guard lock(m);
          got.emplace(id, std::move(s));
        },
        nullptr, &exchange);
  });
  a_is_stepping.wait();
  run_interleaved(
      6, [&](DropletJob*, bool) { return false; },
      [&](std::int64_t id, RunSummary&& s) {
        std::lock_guard lock(m);
        got.emplace(id, std::move(s));
        ++finished_by_b;
      },
      nullptr, &exchange);
  a.join();
  ASSERT_EQ(got.size(), static_cast<std::size_t>(kDroplets));
  for (int i = 0; i < kDroplets; ++i)
    expect_same(got.at(i), solo[static_cast<std::size_t>(i)], "droplet " + std::to_string(i));
  EXPECT_GE(exchange.handovers(), 1);
  EXPECT_GE(finished_by_b, 1);
}

TEST(Interleaved, AWorkerThatFailsStopsTheBatchWithoutHangingTheOthers) {
  // The progress callback fails once 3 droplets are done, on whichever thread: that worker leaves
  // the lane exchange mid-batch, the others finish what they step, and run_batch reports the error.
  const Medium medium = medium_of_porosity_08();
  BatchOptions b;
  b.droplets = 30;
  b.threads = 2;
  RunOptions o;
  o.stuck_window = 0.1;
  int calls = 0;
  EXPECT_THROW(run_batch(DropletParams{}, medium, o, b,
                         [&](int done, int) {
                           ++calls;
                           if (done >= 3) throw std::runtime_error("progress sink failed");
                         }),
               std::runtime_error);
  EXPECT_GE(calls, 3);
  EXPECT_LT(calls, 30);  // no new droplet starts after the failure
}

TEST(Interleaved, ACancelledRunLeavesTheDriver) {
  const Medium pore = test::pore_of_three_grains();
  DropletParams p;
  RunOptions o;
  o.check_interval = 16;
  int checks = 0;
  o.cancelled = [&] { return ++checks > 3; };
  Simulation a(p, pore), b(p, pore);
  int handed = 0, finished = 0;
  EXPECT_THROW(run_interleaved(
                   2,
                   [&](DropletJob* job, bool) {
                     if (handed == 2) return false;
                     *job = {handed == 0 ? &a : &b, 100, &o, handed};
                     ++handed;
                     return true;
                   },
                   [&](std::int64_t, RunSummary&&) { ++finished; }),
               RunCancelled);
  EXPECT_EQ(finished, 0);
  EXPECT_THROW(run_interleaved(
                   0, [](DropletJob*, bool) { return false; }, [](std::int64_t, RunSummary&&) {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace softdrop
