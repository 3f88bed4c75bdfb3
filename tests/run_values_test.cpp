// A search's and a sweep's options as named values (service/run_values.hpp), from which the Python
// module builds its runs: they read back to the same options, carry the program's defaults and
// presets, and refuse an option of a strategy or objective that is not the one chosen. And
// --gap, the one spacing rule of a search's start and moves, as the program stores it.
#include "service/run_values.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "service/search_start.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"

namespace softdrop {
namespace {

TEST(RunValues, ASearchRunReadsBackToTheSameStoredParameters) {
  SearchRun run = default_search_run();
  run.search.lambda = 5;
  run.search.objective.kind = ObjectiveKind::quantile;
  run.start.medium.r_max = 40;
  run.start.medium.seed = 18446744073709551615ULL;  // a seed's whole range survives the JSON
  run.islands = 3;
  run.own_island_starts = true;
  SearchRun back;
  set_search_run_values(search_run_values(run), &back);
  EXPECT_EQ(search_run_values(back), search_run_values(run));
  EXPECT_EQ(back.start.medium.seed, 18446744073709551615ULL);
  EXPECT_EQ(back.search.lambda, 5);
  EXPECT_TRUE(back.own_island_starts);
}

TEST(RunValues, TheDefaultSearchIsTheProgramsAndItsStartIsAGeneratedMedium) {
  const SearchRun d = default_search_run();
  EXPECT_EQ(d.search.strategy.kind, StrategyKind::es);
  EXPECT_EQ(d.search.objective.kind, ObjectiveKind::mean);
  EXPECT_EQ(d.search.lambda, 8);
  EXPECT_EQ(d.search.relocate_every, 3);
  EXPECT_EQ(d.start.medium.grains, 20);
  // The medium's keys are those of the start, not of the search: with a grain file they do nothing.
  const std::vector<std::string>& medium = search_medium_keys();
  for (const char* key : {"grains", "width", "r-min", "walls", "medium-seed"})
    EXPECT_NE(std::find(medium.begin(), medium.end(), key), medium.end()) << key;
  for (const char* key : {"gap", "lambda", "medium"})
    EXPECT_EQ(std::find(medium.begin(), medium.end(), key), medium.end()) << key;
}

TEST(RunValues, ThePaperPresetSetsOnlyWhatWasNotGiven) {
  SearchOptions s = default_search_run().search;
  const std::vector<std::string> set = apply_search_preset("paper", {"lambda"}, &s);
  EXPECT_EQ(set, (std::vector<std::string>{"strategy", "relocate-every", "objective"}));
  EXPECT_EQ(s.strategy.kind, StrategyKind::paper);
  EXPECT_EQ(s.lambda, 8);  // given: kept
  EXPECT_EQ(s.relocate_every, 0);
  EXPECT_EQ(s.objective.kind, ObjectiveKind::single);
  EXPECT_TRUE(apply_search_preset("", {}, &s).empty());
  EXPECT_THROW(apply_search_preset("fast", {}, &s), std::invalid_argument);
}

TEST(RunValues, AnOptionOfAnotherStrategyOrObjectiveIsRefusedNamingBoth) {
  SearchRun run = default_search_run();  // es, mean
  run.db = "never.db";
  std::string why;
  run.given = {"target-success", "starts", "margin"};
  EXPECT_TRUE(run.IsValid(&why)) << why;
  run.given = {"sigma"};
  EXPECT_FALSE(run.IsValid(&why));
  EXPECT_EQ(why, "sigma: an option of --strategy cmaes, not used by --strategy es");
  run.given = {"quantile"};
  EXPECT_FALSE(run.IsValid(&why));
  EXPECT_EQ(why, "quantile: not an option of --objective mean");
  run.resume = 1;  // a resumed run's stored strategy and objective decide
  EXPECT_TRUE(run.IsValid(&why)) << why;
}

TEST(RunValues, ASweepReadsBackAndItsPresetFillsWhatWasNotGiven) {
  SweepOptions s = default_sweep();
  EXPECT_EQ(s.medium.kind, MediumKind::overlapping);
  s.porosities = {0.6, 0.7};
  s.droplet.nrt = 2e9;
  EXPECT_EQ(sweep_params_to_json(sweep_of_values(sweep_values(s), {})), sweep_params_to_json(s));
  SecondDroplet second;
  second.after = 7;
  s.second = second;
  EXPECT_EQ(sweep_params_to_json(sweep_of_values(sweep_values(s), {})), sweep_params_to_json(s));
  // The second droplet's options without one.
  EXPECT_THROW(sweep_of_values(sweep_values(default_sweep()), {"second-after"}), std::invalid_argument);
  SweepOptions q = default_sweep();
  apply_sweep_preset("quick", {"media"}, &q);
  EXPECT_EQ(q.porosities, (std::vector<double>{0.7, 0.8, 0.9}));
  EXPECT_EQ(q.media, default_sweep().media);
  EXPECT_EQ(q.droplets, 8);
  EXPECT_THROW(apply_sweep_preset("slow", {}, &q), std::invalid_argument);
}

TEST(RunValues, GapIsTheSearchsOneSpacingRuleAndIsStored) {
  // The program's --gap makes the starting medium and governs the moves, and the history keeps it.
  const std::string db = test::fresh_path("gap.db");
  const test::Result r = test::run("optimize --db " + db +
                                   " --gap 0.3 --generations 1 --lambda 1 --objective single --validate-starts 0 "
                                   "--quiet --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto runs = open_history(db, OpenMode::read_only)->runs();
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(search_params_from_json(runs[0].params).gap, 0.3);
}

}  // namespace
}  // namespace softdrop
