// The pore-space tortuosities' solves (pore_tortuosity.hpp) on the default box at the resolutions
// `softdrop tortuosity` uses by default: 500 and 1000 pixels across an overlapping medium of
// porosity 0.7 (medium seed 3). One core: the solves are serial.
#include <benchmark/benchmark.h>

#include "softdrop/medium.hpp"
#include "studies/pore_tortuosity.hpp"

namespace {

softdrop::PoreImage image(int pixels) {
  softdrop::MediumOptions o;
  o.porosity = 0.7;
  o.seed = 3;
  return softdrop::pore_image(softdrop::generate_medium(o), pixels);
}

void BM_GeometricTortuosity(benchmark::State& state) {
  const softdrop::PoreImage im = image(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(softdrop::geometric_tortuosity(im).tortuosity);
  state.counters["pixels"] = static_cast<double>(im.pore.size());
}
BENCHMARK(BM_GeometricTortuosity)->Arg(500)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_DiffusiveTortuosity(benchmark::State& state) {
  const softdrop::PoreImage im = image(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(softdrop::diffusive_tortuosity(im).tau);
  state.counters["pixels"] = static_cast<double>(im.pore.size());
}
BENCHMARK(BM_DiffusiveTortuosity)->Arg(500)->Arg(1000)->Unit(benchmark::kMillisecond);

// The creeping flow: two sparse Cholesky factorisations (CHOLMOD) and a dozen pressure iterations.
void BM_HydrodynamicTortuosity(benchmark::State& state) {
  const softdrop::PoreImage im = image(static_cast<int>(state.range(0)));
  int iterations = 0;
  for (auto _ : state) {
    const softdrop::HydrodynamicTortuosity f = softdrop::hydrodynamic_tortuosity(im);
    iterations = f.iterations;
    benchmark::DoNotOptimize(f.tortuosity);
  }
  state.counters["pixels"] = static_cast<double>(im.pore.size());
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_HydrodynamicTortuosity)->Arg(500)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3);

}  // namespace

BENCHMARK_MAIN();
