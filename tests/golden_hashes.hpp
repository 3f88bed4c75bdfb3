#pragma once
// The golden state hashes: each droplet dropped from x = 100 onto the pore of three grains
// (fixtures.hpp) for a fixed number of steps. Update a hash only for a deliberate change of the
// numerics, and say so in the commit. determinism_test.cpp checks them on Simulation::step, and
// layout_hash_test.cpp on every other layout of the step.
#include <cstdint>
#include <string>
#include <vector>

#include "fixtures.hpp"

namespace softdrop::test {

struct GoldenRun {
  std::string name;
  DropletParams params;
  int steps = 0;           ///< steps of the golden state, whatever the droplet does meanwhile
  std::uint64_t hash = 0;  ///< the state hash after them
  /// The run loop's (Simulation::run from x = 100, no stuck or rest test): the droplet passes the
  /// pore at this step, and leaves this state.
  std::int64_t run_steps = 0;
  std::uint64_t run_hash = 0;
};

/// The defaults' droplet falls through the pore for 17 500 steps (0.105 time units; it reaches the
/// grains at about 0.017, leaves the medium at 0.038 and falls on below it).
inline constexpr int kGoldenSteps = 17500;
inline constexpr std::uint64_t kGoldenDefaults = 0x4441aefd57efed83ULL;
/// DropletParams::explicit_step() (results/calibration/explicit.toml): the bits the defaults gave
/// before they took the exponential viscosity step, over the same 0.105 time units in 30 000 steps.
inline constexpr int kGoldenExplicitSteps = 30000;
inline constexpr std::uint64_t kGoldenExplicit = 0xfbf01f57e1e5c063ULL;
/// DropletParams::exponential_step() (results/calibration/exponential.toml): the bits the defaults
/// gave before they took the implicit viscosity step, over kGoldenSteps.
inline constexpr std::uint64_t kGoldenExponential = 0xd2c147d4a78565f2ULL;
/// The balloon (results/calibration/balloon.toml), the earlier defaults, over 5 000 steps; and in
/// the red-black constraint order, with its default ring of 24 masses and an odd one of 25.
inline constexpr int kGoldenBalloonSteps = 5000;
inline constexpr std::uint64_t kGoldenBalloon = 0x545c7e92a6789dc7ULL;
inline constexpr std::uint64_t kGoldenRedBlack[2] = {0xce0c56a92b871a38ULL, 0xea48542fd2b4639cULL};

/// Every golden run above.
inline std::vector<GoldenRun> golden_runs() {
  DropletParams red_black = balloon_droplet();
  red_black.constraint_order = ConstraintOrder::red_black;
  DropletParams odd = red_black;
  odd.masses = 25;
  return {{"defaults", DropletParams{}, kGoldenSteps, kGoldenDefaults, 6379, 0xc41a14844e531fe0ULL},
          {"explicit step", DropletParams::explicit_step(), kGoldenExplicitSteps, kGoldenExplicit, 10988,
           0x46c963b1eb4ba109ULL},
          {"exponential step", DropletParams::exponential_step(), kGoldenSteps, kGoldenExponential, 6408,
           0x4314fe0de497eb0aULL},
          {"balloon", balloon_droplet(), kGoldenBalloonSteps, kGoldenBalloon, 1715, 0x60bda152d9b303b6ULL},
          {"balloon, red-black", red_black, kGoldenBalloonSteps, kGoldenRedBlack[0], 1723, 0x0d8d2aab43599397ULL},
          {"balloon, red-black, 25 masses", odd, kGoldenBalloonSteps, kGoldenRedBlack[1], 1718, 0x0f90de8fff8ccf84ULL}};
}

}  // namespace softdrop::test
