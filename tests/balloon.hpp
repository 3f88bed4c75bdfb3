#pragma once
// The balloon on the command line: the droplet the defaults were before the calibration, which the
// tests of the machinery run on the small scenes laid out for it. Its one command-line spelling is
// results/calibration/balloon.toml (droplet, grains of radii 8 to 16, step budget); fixtures.hpp's
// balloon_droplet() is DropletParams::balloon(), and config_files_test.cpp checks that the two agree
// to the bit.

#include <string>

namespace softdrop::test {

/// The balloon's config file, as command-line options.
inline const std::string kBalloonOptions =
    " --config " + std::string(SOFTDROP_SOURCE_DIR) + "/results/calibration/balloon.toml ";
/// The grains of the balloon's scenes, for the tests that build media in the library.
inline constexpr double kBalloonRMin = 8, kBalloonRMax = 16;

/// The small search scene of search_fixtures.hpp (16 non-overlapping grains in 160 x 120, medium
/// seed 2) with the balloon.
inline const std::string kSmallScene = " --grains 16 --width 160 --height 120 --medium-seed 2 " + kBalloonOptions;

}  // namespace softdrop::test
