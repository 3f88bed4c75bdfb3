// A program of one's own on the softdrop library: generate a medium, push a droplet through it and
// print the outcome and the tortuosity. Built against an installed softdrop:
//   cmake --install build --prefix ~/.local
//   g++ -std=c++20 -O2 push_droplet.cpp -I ~/.local/include -L ~/.local/lib -lsoftdrop_sim -lsoftdrop_media
//   -lsoftdrop_util -ltbb -lgmp -lmpfr -lpng -ltiff
//   ./a.out 250        # the same droplet as `softdrop simulate --x0 250`, the same T to the bit
#include <cstdio>
#include <cstdlib>
#include <softdrop/droplet.hpp>
#include <softdrop/medium.hpp>
#include <softdrop/simulation.hpp>

int main(int argc, char** argv) {
  const double x0 = argc > 1 ? std::atof(argv[1]) : 250.0;
  softdrop::MediumOptions medium_options;  // overlapping grains, porosity 0.8, 500 x 500, as simulate
  const softdrop::Medium medium = softdrop::generate_medium(medium_options);
  softdrop::Simulation simulation(softdrop::DropletParams{}, medium);
  const softdrop::RunSummary run = simulation.run(x0, softdrop::RunOptions{});
  std::printf("outcome %s\ntortuosity %.17g\nsteps %lld\n", softdrop::to_string(run.outcome), run.tortuosity,
              static_cast<long long>(run.steps));
  return run.outcome == softdrop::Outcome::passed ? 0 : 1;
}
