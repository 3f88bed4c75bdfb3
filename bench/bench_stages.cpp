// The stages of one step, each timed on its own (Google Benchmark), for rings of 16, 40 and 128
// masses in the medium-200 scene, with the droplet in contact with grains.
// Run: build/bench/bench_stages --benchmark_out=bench/results/stages.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <functional>

#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace {
using softdrop::Simulation;

// A droplet that has fallen into the medium-200 scene for 3 000 steps: it touches grains. The
// stage runs on a copy of that state, restored every 256 iterations (out of the timing) so that
// the state stays realistic.
void stage(benchmark::State& state, const std::function<void(Simulation&)>& body,
           softdrop::ConstraintOrder order = softdrop::ConstraintOrder::sequential) {
  softdrop::MediumOptions mo;
  mo.porosity = 0.7;
  mo.seed = 1;
  const softdrop::Medium medium = softdrop::generate_medium(mo);
  softdrop::DropletParams p;
  p.masses = static_cast<int>(state.range(0));
  p.constraint_order = order;
  Simulation sim(p, medium);
  sim.place_above(137);
  for (int i = 0; i < 3000; ++i) sim.step();
  sim.compute_forces();
  const softdrop::DropletState saved = sim.state();
  long n = 0;
  for (auto _ : state) {
    body(sim);
    if (++n % 256 == 0) {
      state.PauseTiming();
      sim.mutable_state() = saved;
      state.ResumeTiming();
    }
  }
  state.counters["mass-updates/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * p.masses, benchmark::Counter::kIsRate);
}

void BM_SpringsAndPressure(benchmark::State& s) {
  stage(s, [](Simulation& sim) {
    sim.accumulate_gravity();
    sim.accumulate_springs();
    sim.accumulate_pressure();
  });
}
void BM_Collisions(benchmark::State& s) { stage(s, [](Simulation& sim) { sim.accumulate_collisions(); }); }
void BM_Viscosity(benchmark::State& s) { stage(s, [](Simulation& sim) { sim.accumulate_viscosity(); }); }
void BM_Integrate(benchmark::State& s) { stage(s, [](Simulation& sim) { sim.integrate(); }); }
void BM_ConstraintSequential(benchmark::State& s) {
  stage(s, [](Simulation& sim) { sim.integrate(); sim.apply_constraint(); });
}
void BM_ConstraintRedBlack(benchmark::State& s) {
  stage(s, [](Simulation& sim) { sim.integrate(); sim.apply_constraint(); }, softdrop::ConstraintOrder::red_black);
}
void BM_ContactLimit(benchmark::State& s) { stage(s, [](Simulation& sim) { sim.apply_contact_limit(); }); }
void BM_WholeStep(benchmark::State& s) { stage(s, [](Simulation& sim) { sim.step(); }); }

#define SIZES ->Arg(16)->Arg(40)->Arg(128)
BENCHMARK(BM_SpringsAndPressure) SIZES;
BENCHMARK(BM_Collisions) SIZES;
BENCHMARK(BM_Viscosity) SIZES;
BENCHMARK(BM_Integrate) SIZES;
BENCHMARK(BM_ConstraintSequential) SIZES;
BENCHMARK(BM_ConstraintRedBlack) SIZES;
BENCHMARK(BM_ContactLimit) SIZES;
BENCHMARK(BM_WholeStep) SIZES;

}  // namespace

BENCHMARK_MAIN();
