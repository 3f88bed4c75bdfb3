// The stages of one step, each timed on its own (Google Benchmark), for rings of 16, 24 (the
// defaults), 40 and 128 masses in the medium-200 scene, with the droplet in contact with grains.
// Run: build/bench/bench_stages --benchmark_out=bench/results/stages.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench_media.hpp"
#include "sim/lane_layout.hpp"
#include "sim/lane_policy.hpp"
#include "sim/step_driver.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace {
using softdrop::run_stage;
using softdrop::Simulation;
using softdrop::StepStage;

// A droplet pressed against grains of the medium-200 scene (bench::droplet_in_contact). The stage
// runs on a copy of that state, restored every 256 iterations (out of the timing) so that the
// state stays realistic.
// Times `body`, putting the simulations back in their first state every 256 iterations (untimed),
// so that the droplets stay in contact with the grains however long the benchmark runs.
void timed_in_contact(benchmark::State& state, const std::vector<std::unique_ptr<Simulation>>& sims,
                      const std::function<void()>& body) {
  std::vector<softdrop::DropletState> saved;
  for (const auto& sim : sims) saved.push_back(sim->state());
  long n = 0;
  for (auto _ : state) {
    body();
    if (++n % 256 == 0) {
      state.PauseTiming();
      for (std::size_t i = 0; i < sims.size(); ++i) sims[i]->mutable_state() = saved[i];
      state.ResumeTiming();
    }
  }
}

void stage(benchmark::State& state, const std::function<void(Simulation&)>& body,
           softdrop::ConstraintOrder order = softdrop::ConstraintOrder::sequential) {
  const softdrop::Medium medium = softdrop::bench::medium_200();
  softdrop::DropletParams p;
  p.masses = static_cast<int>(state.range(0));
  p.constraint_order = order;
  std::vector<std::unique_ptr<Simulation>> sims;
  sims.push_back(softdrop::bench::droplet_in_contact(p, medium));
  Simulation& sim = *sims[0];
  timed_in_contact(state, sims, [&] { body(sim); });
  state.counters["mass-updates/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * p.masses, benchmark::Counter::kIsRate);
}

void BM_SpringsAndPressure(benchmark::State& s) {
  stage(s, [](Simulation& sim) {
    run_stage<StepStage::gravity>(sim);
    run_stage<StepStage::springs>(sim);
    run_stage<StepStage::pressure>(sim);
  });
}
// Stages run again on positions they have seen, so the collisions take the contact limit's record
// of the grains each mass is inside, and the contact limit skips masses within their clearance, as
// for masses that did not move far in a run (67 % of the contact limit's masses in the batch scene
// are skipped); bench_scenes shows what whole runs gain.
// The collisions as a step after any change of the state runs them: every mass tested against its
// record (after the first iteration the contact limit's recorded forces are spent).
void BM_Collisions(benchmark::State& s) {
  stage(s, [](Simulation& sim) { run_stage<StepStage::collisions>(sim); });
}
// The contact limit and the next collisions, as a step runs them: the forces the contact limit
// records for the masses inside one disc are added with no test.
void BM_ContactLimitThenCollisions(benchmark::State& s) {
  stage(s, [](Simulation& sim) {
    run_stage<StepStage::contact_limit>(sim);
    run_stage<StepStage::collisions>(sim);
  });
}
void BM_Viscosity(benchmark::State& s) {
  stage(s, [](Simulation& sim) { run_stage<StepStage::viscosity>(sim); });
}
void BM_Integrate(benchmark::State& s) {
  stage(s, [](Simulation& sim) { run_stage<StepStage::integrate>(sim); });
}
void BM_ConstraintSequential(benchmark::State& s) {
  stage(s, [](Simulation& sim) {
    run_stage<StepStage::integrate>(sim);
    run_stage<StepStage::constraint>(sim);
  });
}
void BM_ConstraintRedBlack(benchmark::State& s) {
  stage(
      s,
      [](Simulation& sim) {
        run_stage<StepStage::integrate>(sim);
        run_stage<StepStage::constraint>(sim);
      },
      softdrop::ConstraintOrder::red_black);
}
// The red-black constraint at a given vector width (1 scalar, 2 SSE2, 4 AVX, 8 AVX-512; the same bits): what
// each width buys where the processor has it.
void BM_ConstraintRedBlackAtWidth(benchmark::State& s) {
  const softdrop::VectorWidth used =
      softdrop::limit_constraint_vector_width(static_cast<softdrop::VectorWidth>(s.range(1)));
  s.SetLabel("width " + std::to_string(static_cast<int>(used)));
  stage(
      s,
      [](Simulation& sim) {
        run_stage<StepStage::integrate>(sim);
        run_stage<StepStage::constraint>(sim);
      },
      softdrop::ConstraintOrder::red_black);
  softdrop::limit_constraint_vector_width(softdrop::VectorWidth::avx512);
}
void BM_ContactLimit(benchmark::State& s) {
  stage(s, [](Simulation& sim) { run_stage<StepStage::contact_limit>(sim); });
}
void BM_WholeStep(benchmark::State& s) {
  stage(s, [](Simulation& sim) { sim.step(); });
}

// The floor under one droplet's sequential constraint: only the operations its chain of links
// depends on (the spring's difference from the mass the previous link moved, squared length,
// square root, (d - target) / (d + d), the far end moved), for every spring of every pass, as in
// the balloon's state, where every spring is corrected (bench/README.md). No test, store or count,
// and the far ends are read from memory that nothing writes, so the time is the chain's latency.
// Compare BM_ConstraintSequential (integration + the real constraint): a lone droplet's sequential
// step cannot take less than this, however the rest of the step is written. links/s is per link.
void BM_ConstraintChainFloor(benchmark::State& s) {
  const softdrop::Medium medium = softdrop::bench::medium_200();
  softdrop::DropletParams p;
  p.masses = static_cast<int>(s.range(0));
  const auto sim = softdrop::bench::droplet_in_contact(p, medium);
  run_stage<StepStage::integrate>(*sim);  // the positions the constraint sees
  const std::vector<double> x = sim->state().x, y = sim->state().y;
  const double dmax = (1 + p.max_strain) * p.rest_length();
  const int n = p.masses, passes = p.constraint_iterations;
  for (auto _ : s) {
    double xi = x[0], yi = y[0];
    for (int pass = 0; pass < passes; ++pass)
      for (int i = 0; i < n; ++i) {
        const std::size_t j = i + 1 == n ? 0 : static_cast<std::size_t>(i) + 1;
        const double dx = x[j] - xi, dy = y[j] - yi;
        const double d = std::sqrt(dx * dx + dy * dy);
        const double c = (d - dmax) / (d + d);
        xi = x[j] - c * dx;
        yi = y[j] - c * dy;
      }
    benchmark::DoNotOptimize(xi);
    benchmark::DoNotOptimize(yi);
  }
  s.counters["links/s"] =
      benchmark::Counter(static_cast<double>(s.iterations()) * n * passes, benchmark::Counter::kIsRate);
  s.counters["mass-updates/s"] =
      benchmark::Counter(static_cast<double>(s.iterations()) * n, benchmark::Counter::kIsRate);
}

// The sequential constraint on K rings at once (apply_length_constraint_interleaved), as a batch of
// droplets steps them: K copies of the stage's state, each integrated, then constrained together,
// at vector width W (the widest the processor has, at most W). Time per iteration covers all K
// rings; mass-updates/s counts all of them.
void BM_ConstraintSequentialInterleaved(benchmark::State& state) {
  const int rings = static_cast<int>(state.range(1));
  const softdrop::VectorWidth used =
      softdrop::limit_constraint_vector_width(static_cast<softdrop::VectorWidth>(state.range(2)));
  state.SetLabel("width " + std::to_string(static_cast<int>(used)));
  const softdrop::Medium medium = softdrop::bench::medium_200();
  softdrop::DropletParams p;
  p.masses = static_cast<int>(state.range(0));
  std::vector<std::unique_ptr<Simulation>> sims;
  for (int r = 0; r < rings; ++r) sims.push_back(softdrop::bench::droplet_in_contact(p, medium));
  std::vector<softdrop::DropletState*> states;
  for (auto& sim : sims) states.push_back(&sim->mutable_state());
  std::vector<int> corrections(static_cast<std::size_t>(rings));
  timed_in_contact(state, sims, [&] {
    for (auto& sim : sims) run_stage<StepStage::integrate>(*sim);
    softdrop::apply_length_constraint_interleaved(states.data(), rings, p.rest_length(), p.max_strain,
                                                  p.constraint_iterations, corrections.data());
  });
  state.counters["mass-updates/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * p.masses * rings, benchmark::Counter::kIsRate);
  softdrop::limit_constraint_vector_width(softdrop::VectorWidth::avx512);
}
// The stages a batch steps lane by lane (run_interleaved with AVX-512 or AVX, src/sim/lane_layout.hpp)
// on K rings in contact, 8 to a group, at vector width W (8: AVX-512, 4: AVX): gravity, springs
// and pressure; viscosity; the copies in and out of the lane-by-lane layout a step makes (x, y,
// px, py in; x, y out). Time per iteration covers all K rings; seconds/ring is the time per ring.
template <class Body>
void lane_stage(benchmark::State& state, std::int64_t width, const std::string& what, const Body& body) {
  const softdrop::VectorWidth used = softdrop::limit_constraint_vector_width(static_cast<softdrop::VectorWidth>(width));
  if (used < softdrop::VectorWidth::avx) {
    state.SkipWithError("needs AVX");
    softdrop::limit_constraint_vector_width(softdrop::VectorWidth::avx512);
    return;
  }
  state.SetLabel(what + "width " + std::to_string(static_cast<int>(used)));
  const int rings = static_cast<int>(state.range(1)), registers = (rings + 7) / 8, lanes = 8 * registers;
  const softdrop::Medium medium = softdrop::bench::medium_200();
  softdrop::DropletParams p;
  p.masses = static_cast<int>(state.range(0));
  std::vector<std::unique_ptr<Simulation>> sims;
  for (int r = 0; r < rings; ++r) sims.push_back(softdrop::bench::droplet_in_contact(p, medium));
  const std::size_t size = static_cast<std::size_t>(p.masses) * static_cast<std::size_t>(lanes);
  std::vector<double> block(6 * size);
  double* const a[6] = {block.data(),
                        block.data() + size,
                        block.data() + 2 * size,
                        block.data() + 3 * size,
                        block.data() + 4 * size,
                        block.data() + 5 * size};
  std::vector<double*> in[4];
  for (int t = 0; t < lanes; ++t) {
    softdrop::DropletState& st = sims[static_cast<std::size_t>(std::min(t, rings - 1))]->mutable_state();
    in[0].push_back(st.x.data());
    in[1].push_back(st.y.data());
    in[2].push_back(st.px.data());
    in[3].push_back(st.py.data());
  }
  for (int k = 0; k < 4; ++k) softdrop::lanes::copy_in(in[k].data(), a[k], p.masses, registers);
  const softdrop::StepContext c = softdrop::make_step_context(p);
  std::vector<double> area(softdrop::lanes::kMaxLanes);
  softdrop::lanes::forces_before_contacts(c, a[0], a[1], a[2], a[3], a[4], a[5], area.data(), p.masses, registers);
  long k = 0;
  for (auto _ : state) {
    body(c, a, in, p.masses, registers);
    if (++k % 256 == 0) {  // back to the droplets' states, so that they stay in contact
      state.PauseTiming();
      for (int b = 0; b < 4; ++b) softdrop::lanes::copy_in(in[b].data(), a[b], p.masses, registers);
      state.ResumeTiming();
    }
  }
  state.counters["mass-updates/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * p.masses * rings, benchmark::Counter::kIsRate);
  state.counters["seconds/ring"] = benchmark::Counter(static_cast<double>(state.iterations()) * rings,
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  softdrop::limit_constraint_vector_width(softdrop::VectorWidth::avx512);
}
void BM_LaneForces(benchmark::State& s) {
  std::vector<double> area(softdrop::lanes::kMaxLanes);
  lane_stage(s, s.range(2), "",
             [&](const softdrop::StepContext& c, double* const* a, std::vector<double*>*, int n, int r) {
               softdrop::lanes::forces_before_contacts(c, a[0], a[1], a[2], a[3], a[4], a[5], area.data(), n, r);
               benchmark::DoNotOptimize(a[4][0]);
             });
}
void BM_LaneViscosity(benchmark::State& s) {
  lane_stage(s, s.range(2), "",
             [](const softdrop::StepContext& c, double* const* a, std::vector<double*>*, int n, int r) {
               softdrop::lanes::viscosity(c, a[0], a[1], a[2], a[3], a[4], a[5], n, r);
               benchmark::DoNotOptimize(a[4][0]);
             });
}
void BM_LaneCopies(benchmark::State& s) {
  lane_stage(s, s.range(2), "",
             [](const softdrop::StepContext&, double* const* a, std::vector<double*>* in, int n, int r) {
               for (int k = 0; k < 4; ++k) softdrop::lanes::copy_in(in[k].data(), a[k], n, r);
               for (int k = 0; k < 2; ++k) softdrop::lanes::copy_out(in[k].data(), a[k], n, r);
             });
}
// Integration and each constraint order lane by lane, as BM_ConstraintSequentialInterleaved but
// without its copies in and out.
void BM_LaneConstraint(benchmark::State& s) {
  const bool red_black = s.range(2) != 0;
  softdrop::DropletParams p;
  const double dmax = (1 + p.max_strain) * p.rest_length(), dmin = (1 - p.max_strain) * p.rest_length();
  std::vector<int> counts(softdrop::lanes::kMaxLanes);
  lane_stage(
      s, s.range(3), red_black ? "red-black, " : "sequential, ",
      [&](const softdrop::StepContext& c, double* const* a, std::vector<double*>*, int n, int r) {
        softdrop::lanes::integrate(c.h2m, a[0], a[1], a[2], a[3], a[4], a[5], n, r);
        if (red_black)
          softdrop::lanes::constrain_red_black(a[0], a[1], n, r, p.constraint_iterations, dmin, dmax, counts.data());
        else
          softdrop::lanes::constrain_sequential(a[0], a[1], n, r, p.constraint_iterations, dmin, dmax, counts.data());
      });
}
BENCHMARK(BM_LaneConstraint)->ArgsProduct({{24}, {8, 16, 24}, {0, 1}, {8, 4}});
BENCHMARK(BM_LaneForces)->ArgsProduct({{24}, {8, 24}, {8, 4}});
BENCHMARK(BM_LaneViscosity)->ArgsProduct({{24}, {8, 24}, {8, 4}});
BENCHMARK(BM_LaneCopies)->ArgsProduct({{24}, {8, 24}, {8, 4}});

BENCHMARK(BM_ConstraintSequentialInterleaved)->ArgsProduct({{24}, {1, 2, 3, 4, 6, 8, 10, 12}, {4}});
BENCHMARK(BM_ConstraintSequentialInterleaved)->ArgsProduct({{24}, {1, 8, 12, 16, 20, 24}, {8}});
BENCHMARK(BM_ConstraintSequentialInterleaved)->ArgsProduct({{24}, {6}, {2}});
BENCHMARK(BM_ConstraintRedBlackAtWidth)->ArgsProduct({{24}, {1, 2, 4, 8}});

#define SIZES ->Arg(16)->Arg(24)->Arg(40)->Arg(128)
BENCHMARK(BM_SpringsAndPressure) SIZES;
BENCHMARK(BM_Collisions) SIZES;
BENCHMARK(BM_Viscosity) SIZES;
BENCHMARK(BM_Integrate) SIZES;
BENCHMARK(BM_ConstraintSequential) SIZES;
BENCHMARK(BM_ConstraintRedBlack) SIZES;
BENCHMARK(BM_ContactLimit) SIZES;
BENCHMARK(BM_ContactLimitThenCollisions) SIZES;
BENCHMARK(BM_WholeStep) SIZES;
BENCHMARK(BM_ConstraintChainFloor) SIZES;

}  // namespace

BENCHMARK_MAIN();
