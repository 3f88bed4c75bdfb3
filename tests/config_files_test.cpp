// The configs installed with the program (results/calibration/*.toml) are the library's named
// droplets: through the same medium from the same start, the command line with the file and the
// library with the factory give the same bits.
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "balloon.hpp"
#include "cli_run.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {
using test::run;

// `softdrop --config results/calibration/FILE simulate --x0 250` as JSON.
nlohmann::json simulate_with(const std::string& file) {
  const auto r = run("--config " + std::string(SOFTDROP_SOURCE_DIR) + "/results/calibration/" + file +
                     " simulate --x0 250 --format json");
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

void expect_same_run(const nlohmann::json& j, const RunSummary& s) {
  ASSERT_EQ(s.outcome, Outcome::passed) << s.reason;
  EXPECT_EQ(j["run"]["tortuosity"].get<double>(), s.tortuosity);
  EXPECT_EQ(j["run"]["steps"].get<std::int64_t>(), s.steps);
}

// balloon.toml is DropletParams::balloon() on grains of radii 8 to 16, with the balloon's step
// budget.
TEST(ConfigFiles, TheBalloonConfigIsTheLibrarysBalloon) {
  const auto j = simulate_with("balloon.toml");
  MediumOptions mo;
  mo.r_min = test::kBalloonRMin, mo.r_max = test::kBalloonRMax;
  const Medium medium = generate_medium(mo);
  RunOptions o;
  o.max_steps = 2'000'000;
  expect_same_run(j, Simulation(DropletParams::balloon(), medium).run(250, o));
  EXPECT_EQ(j["medium"]["grains"].get<std::size_t>(), medium.grains.size());
}

// explicit.toml is DropletParams::explicit_step(), at 1.7 times the defaults' steps.
TEST(ConfigFiles, TheExplicitConfigIsTheLibrarysExplicitStepDroplet) {
  const auto j = simulate_with("explicit.toml");
  const Medium medium = generate_medium(MediumOptions{});
  const RunSummary s = Simulation(DropletParams::explicit_step(), medium).run(250, RunOptions{});
  expect_same_run(j, s);
  const RunSummary fast = Simulation(DropletParams{}, medium).run(250, RunOptions{});
  EXPECT_GT(2 * s.steps, 3 * fast.steps);  // the defaults' dt is 1.7 times explicit_step()'s
}

// exponential.toml is DropletParams::exponential_step(), which differs from the defaults.
TEST(ConfigFiles, TheExponentialConfigIsTheLibrarysExponentialStepDroplet) {
  const auto j = simulate_with("exponential.toml");
  const Medium medium = generate_medium(MediumOptions{});
  const RunSummary s = Simulation(DropletParams::exponential_step(), medium).run(250, RunOptions{});
  expect_same_run(j, s);
  EXPECT_NE(Simulation(DropletParams{}, medium).run(250, RunOptions{}).tortuosity, s.tortuosity);
}

// passage.toml is DropletParams::passage() on grains of radii 26 to 50, and differs from the
// defaults' droplet on those grains.
TEST(ConfigFiles, ThePassageConfigIsTheLibrarysPassageDroplet) {
  const auto j = simulate_with("passage.toml");
  MediumOptions mo;
  mo.r_min = 26, mo.r_max = 50;
  const Medium medium = generate_medium(mo);
  const RunSummary s = Simulation(DropletParams::passage(), medium).run(250, RunOptions{});
  expect_same_run(j, s);
  EXPECT_EQ(j["medium"]["grains"].get<std::size_t>(), medium.grains.size());
  EXPECT_NE(Simulation(DropletParams{}, medium).run(250, RunOptions{}).tortuosity, s.tortuosity);
}

// relaxed.toml is a medium, not a droplet: relaxed grains with gaps of 0.4, the default droplet.
TEST(ConfigFiles, TheRelaxedConfigIsARelaxedMediumWithWideGaps) {
  const auto j = simulate_with("relaxed.toml");
  MediumOptions mo;
  mo.kind = MediumKind::relaxed, mo.gap = 0.4;
  const Medium medium = generate_medium(mo);
  expect_same_run(j, Simulation(DropletParams{}, medium).run(250, RunOptions{}));
  EXPECT_EQ(j["medium"]["grains"].get<std::size_t>(), medium.grains.size());
  EXPECT_EQ(j["medium"]["porosity"].get<double>(), exact_porosity(medium));
}

}  // namespace
}  // namespace softdrop
