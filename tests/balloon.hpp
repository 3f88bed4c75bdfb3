#pragma once
// The balloon on the command line: the droplet the defaults were before the calibration
// (results/calibration/balloon.toml; fixtures.hpp's balloon_droplet() is the same droplet), which
// the tests of the machinery run on the small scenes laid out for it.

#include <string>

namespace softdrop::test {

/// The balloon's droplet options, and the grains its scenes use (radii 8 to 16).
inline const std::string kBalloonOptions =
    " --nrt 1.5e9 --ks 119755 --kd 365 --cc 2e4 --dt 2e-5 --viscosity 3000 --viscosity-dilation 1 ";
inline constexpr double kBalloonRMin = 8, kBalloonRMax = 16;

/// The small search scene of search_fixtures.hpp (16 non-overlapping grains in 160 x 120, medium
/// seed 2) with the balloon.
inline const std::string kSmallScene =
    " --grains 16 --width 160 --height 120 --r-min 8 --r-max 16 --medium-seed 2 " + kBalloonOptions;

}  // namespace softdrop::test
