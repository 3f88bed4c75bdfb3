// Cost of one droplet step through a medium, for droplets of 16, 24 (the defaults), 40 and 128
// masses.
// Run: build/bench/bench_step --benchmark_out=bench/results/step.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include "bench_media.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace {

// An overlapping medium of about 200 grains at porosity 0.7; the droplet is dropped again from
// the top whenever it leaves the medium or comes to rest, so every step is a step in the medium.
void BM_StepMedium200(benchmark::State& state) {
  const softdrop::Medium medium = softdrop::bench::medium_200();
  softdrop::DropletParams p;
  p.masses = static_cast<int>(state.range(0));
  softdrop::Simulation sim(p, medium);
  double x0 = 37;
  sim.place_above(x0);
  std::int64_t since_reset = 0;
  for (auto _ : state) {
    sim.step();
    if (++since_reset == 20000) {  // long enough for a full pass or to come to rest
      x0 = x0 + 97 > medium.width ? x0 + 97 - medium.width : x0 + 97;
      sim.place_above(x0);
      since_reset = 0;
    }
  }
  state.counters["grains"] = static_cast<double>(medium.grains.size());
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["mass-updates/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * p.masses, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StepMedium200)->Arg(16)->Arg(24)->Arg(40)->Arg(128);

void BM_ExactPorosity(benchmark::State& state) {
  softdrop::MediumOptions mo;
  mo.porosity = 0.7;
  mo.width = mo.height = 500.0 * static_cast<double>(state.range(0));
  const softdrop::Medium medium = softdrop::generate_medium(mo);
  for (auto _ : state) benchmark::DoNotOptimize(softdrop::exact_porosity(medium));
  state.counters["grains"] = static_cast<double>(medium.grains.size());
}
BENCHMARK(BM_ExactPorosity)->Arg(1)->Arg(5);

}  // namespace

BENCHMARK_MAIN();
