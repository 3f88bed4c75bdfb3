// simulate --from-sweep DB --sweep-droplet P:M:D: every droplet of a stored sweep runs again to
// its stored outcome, T and steps, with the sweep's own medium, droplet and exit options; what
// the sweep sets cannot be given beside it, and a refusal changes no file.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "softdrop/store.hpp"

namespace softdrop {
namespace {

using test::fresh_path;
using test::run;

// The balloon's droplet, a 200 x 200 box and a rest test of its own: none of them the defaults.
std::string sweep_options() {
  return std::string(" --config ") + SOFTDROP_SOURCE_DIR +
         "/results/calibration/balloon.toml --porosities 0.7,0.9 --media 2 --droplets 4 --width 200 --height 200 "
         "--rest-window 0.02 --quiet";
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SweepDropletCli, EveryDropletOfASweepRunsAgainToItsStoredBits) {
  const std::string db = fresh_path("sweep_droplet.db");
  ASSERT_EQ(run("sweep --db " + db + sweep_options()).code, 0);
  auto store = open_sweep_store(db, OpenMode::read_only);
  int runs = 0, passed = 0;
  for (const SweepMedium& m : store->media(1)) {
    // The medium read alone is the same record, its droplets all and only its own.
    const std::optional<SweepMedium> alone = store->medium(1, m.unit);
    ASSERT_TRUE(alone.has_value());
    EXPECT_EQ(alone->medium_seed, m.medium_seed);
    ASSERT_EQ(alone->droplets.size(), m.droplets.size());
    for (std::size_t i = 0; i < m.droplets.size(); ++i) {
      EXPECT_EQ(alone->droplets[i].droplet, m.droplets[i].droplet);
      EXPECT_EQ(alone->droplets[i].steps, m.droplets[i].steps);
    }
    for (const SweepDroplet& d : m.droplets) {
      const std::string name =
          std::to_string(m.unit.porosity) + ":" + std::to_string(m.unit.medium) + ":" + std::to_string(d.droplet);
      const test::Result r = run("simulate --from-sweep " + db + " --sweep-droplet " + name + " --format json");
      ASSERT_EQ(r.code, 0) << name << ": " << r.err;
      const nlohmann::json again = nlohmann::json::parse(r.out).at("run");
      EXPECT_EQ(again.at("outcome"), to_string(d.outcome)) << name;
      EXPECT_EQ(again.at("steps").get<std::int64_t>(), d.steps) << name;
      EXPECT_EQ(again.at("start_x").get<double>(), d.start_x) << name;
      if (d.outcome == Outcome::passed) {
        ++passed;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(again.at("tortuosity").get<double>()),
                  std::bit_cast<std::uint64_t>(d.tortuosity))
            << name;
      }
      // The program says which droplet it ran, and what the sweep stored of it.
      EXPECT_NE(r.err.find("droplet " + name + " of sweep 1"), std::string::npos) << r.err;
      ++runs;
    }
  }
  EXPECT_EQ(runs, 16);
  EXPECT_GT(passed, 0);
}

TEST(SweepDropletCli, WhatTheSweepSetsIsRefusedByNameAndNoFileChanges) {
  const std::string db = fresh_path("sweep_droplet_refused.db");
  ASSERT_EQ(run("sweep --db " + db + sweep_options()).code, 0);
  const std::string before = bytes_of(db);
  const std::string json = fresh_path("sweep_droplet_refused.json");
  for (const auto& [args, says] : {
           std::pair<std::string, std::string>{"--sweep-droplet 0:1:2 --porosity 0.5",
                                               "porosity: the sweep's droplet sets it"},
           {"--sweep-droplet 0:1:2 --nrt 3e9", "nrt: the sweep's droplet sets it"},
           {"--sweep-droplet 0:1:2 --rest-window 0.05", "rest-window: the sweep's droplet sets it"},
           {"--sweep-droplet 0:1:2 --x0 5", "x0: the sweep's droplet sets it"},
           {"--sweep-droplet 0:1", "sweep-droplet = '0:1': expected P:M:D"},
           {"--sweep-droplet 0:2:0", "medium_index = 2: must be in [0, 2)"},
           {"--sweep-droplet 0:0:4", "droplet = 4: must be in [0, 4)"},
           {"", "from-sweep: --sweep-droplet P:M:D names the droplet"},
       }) {
    const test::Result r = run("simulate --from-sweep " + db + " " + args + " --json " + json);
    EXPECT_EQ(r.code, 1) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(json)) << args;
  }
  EXPECT_NE(run("simulate --sweep-droplet 0:1:2").err.find("sweep-droplet: has no effect without --from-sweep"),
            std::string::npos);
  EXPECT_NE(run("simulate --from-sweep " + db + " --sweep-droplet 0:1:2 --sweep-id 2").err.find("sweep-id = 2: '"),
            std::string::npos);
  const std::string missing = fresh_path("sweep_droplet_missing.db");
  EXPECT_NE(run("simulate --from-sweep " + missing + " --sweep-droplet 0:1:2")
                .err.find("--from-sweep '" + missing + "': no such file"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(missing));
  EXPECT_EQ(bytes_of(db), before);
}

}  // namespace
}  // namespace softdrop
