// A search's run on a history file (softdrop/service.hpp), as the program and the Python module
// run it: what its observer hears, a run stopped by the observer and resumed to the same bits,
// the check of given options against a stored run, and what a refused run leaves on disk.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "search_fixtures.hpp"
#include "softdrop/service.hpp"
#include "softdrop/store.hpp"

namespace softdrop {
namespace {

// A search of the small scene (search_fixtures.hpp), 2 candidates a generation.
SearchRun small_run(const std::string& db, std::int64_t generations) {
  SearchRun r;
  r.search = test::small_search_options(2);
  r.start.medium.kind = MediumKind::non_overlapping;
  r.start.medium.grains = 16;
  r.start.medium.width = 160, r.start.medium.height = 120;
  r.start.medium.r_min = test::kBalloonRMin, r.start.medium.r_max = test::kBalloonRMax;
  r.start.medium.seed = 2;
  r.db = db;
  r.generations = generations;
  r.threads = 2;
  r.validate_starts = 0;
  return r;
}

// Records what it hears; stops after `stop_after` generations (0: never).
struct SearchRecorder : SearchObserver {
  std::int64_t stop_after = 0;
  std::vector<std::int64_t> started_with;  // run, from, target, resumed
  std::vector<std::int64_t> generations;
  int validated = 0;
  int refused = 0;
  void start_refused(int attempt, const std::string&) override { refused = attempt; }
  void started(std::int64_t run, const Configuration&, std::int64_t from, std::int64_t target, bool resumed) override {
    started_with = {run, from, target, resumed ? 1 : 0};
  }
  std::vector<std::int64_t> island_runs;
  std::vector<int> islands_heard;
  void islands_started(const std::vector<std::int64_t>& runs, const std::vector<std::int64_t>&,
                       const std::vector<Configuration>&, std::int64_t, bool) override {
    island_runs = runs;
  }
  bool generation(std::int64_t, int island, const Generation& g, const Configuration&, std::int64_t) override {
    islands_heard.push_back(island);
    generations.push_back(g.number);
    return stop_after == 0 || static_cast<std::int64_t>(generations.size()) < stop_after;
  }
  void validating(int done, int total) override { validated = done == total ? total : validated; }
};

// Each stored generation's best T and kept candidate, to the bit.
std::vector<std::uint64_t> history_bits(const std::string& db, std::int64_t run) {
  std::vector<std::uint64_t> bits;
  for (const GenerationRecord& g : open_history(db, OpenMode::read_only)->generations(run))
    bits.push_back(std::bit_cast<std::uint64_t>(g.best_t)), bits.push_back(static_cast<std::uint64_t>(g.accepted));
  return bits;
}

TEST(SearchService, ARunStoresEveryGenerationAndItsHeldOutValue) {
  const std::string db = test::fresh_path("search_service_whole.db");
  SearchRun run = small_run(db, 4);
  run.validate_starts = 6;
  SearchRecorder heard;
  const SearchRunSummary s = run_search(run, heard);
  EXPECT_EQ(s.run, 1);
  EXPECT_FALSE(s.resumed);
  EXPECT_EQ(s.target, 4);
  EXPECT_EQ(s.drive.termination, Termination::generations);
  EXPECT_EQ(s.drive.last_generation, 4);
  EXPECT_EQ(s.initial_evaluations, 1);
  EXPECT_EQ(heard.started_with, (std::vector<std::int64_t>{1, 0, 4, 0}));
  EXPECT_EQ(heard.generations, (std::vector<std::int64_t>{1, 2, 3, 4}));
  EXPECT_EQ(heard.validated, 12);  // 6 starts at dt and 6 at dt/2
  ASSERT_TRUE(s.held_out.has_value());
  EXPECT_EQ(s.held_out->starts, 6);
  EXPECT_EQ(s.held_out->generation, s.best.generation);
  auto history = open_history(db, OpenMode::read_only);
  const RunRecord rec = history->run(1);
  EXPECT_EQ(rec.status, "finished");
  EXPECT_EQ(rec.generations, 4);
  EXPECT_EQ(rec.best_t, s.best.eval.tortuosity);
  ASSERT_EQ(history->validations(1).size(), 1u);
  EXPECT_EQ(history->validations(1)[0].mean_t, s.held_out->mean_t);
  std::filesystem::remove(db);
}

TEST(SearchService, AStoppedRunResumesToTheSameBitsAndAGivenOptionMustMatch) {
  const std::string whole = test::fresh_path("search_service_reference.db"),
                    parts = test::fresh_path("search_service_parts.db");
  SearchRecorder reference;
  const SearchRunSummary r = run_search(small_run(whole, 6), reference);
  SearchRecorder first;
  first.stop_after = 2;
  const SearchRunSummary s = run_search(small_run(parts, 6), first);
  EXPECT_EQ(s.drive.termination, Termination::callback);
  EXPECT_EQ(s.drive.last_generation, 2);
  EXPECT_FALSE(s.held_out.has_value());  // a stopped run is left to `softdrop validate`
  EXPECT_EQ(open_history(parts, OpenMode::read_only)->run(1).status, "interrupted");

  // A resume that contradicts the run in an option it gives is refused, and writes nothing.
  SearchRun resume = small_run(parts, 6);
  resume.resume = 1;
  resume.generations.reset();  // the run's own target
  resume.search.lambda = 3;
  resume.given = {"lambda"};
  SearchRecorder refused;
  try {
    run_search(resume, refused);
    FAIL() << "a contradicting lambda was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--lambda 3 (stored 2)"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(refused.started_with.empty());
  EXPECT_EQ(open_history(parts, OpenMode::read_only)->run(1).generations, 2);
  // Not given, the same difference is the stored run's to decide.
  resume.given.clear();
  SearchRecorder second;
  const SearchRunSummary t = run_search(resume, second);
  EXPECT_TRUE(t.resumed);
  EXPECT_EQ(t.search.lambda, 2);
  EXPECT_EQ(t.target, 6);
  EXPECT_EQ(second.started_with, (std::vector<std::int64_t>{1, 2, 6, 1}));
  EXPECT_EQ(t.drive.termination, Termination::generations);
  EXPECT_EQ(t.best.eval.tortuosity, r.best.eval.tortuosity);
  EXPECT_EQ(history_bits(parts, 1), history_bits(whole, 1));
  // At its target, a resume has nothing to do and changes nothing.
  const SearchRunSummary u = run_search(resume, second);
  EXPECT_TRUE(u.nothing_to_do);
  EXPECT_EQ(u.drive.last_generation, 6);
  EXPECT_EQ(u.best.eval.tortuosity, r.best.eval.tortuosity);
  EXPECT_EQ(history_bits(parts, 1), history_bits(whole, 1));
  std::filesystem::remove(whole);
  std::filesystem::remove(parts);
}

TEST(SearchService, ARefusedRunNamesTheOptionAndWritesNoFile) {
  const std::string db = test::fresh_path("search_service_refused.db");
  SearchRecorder heard;
  const auto refused_naming = [&](const SearchRun& run, const std::string& name) {
    try {
      run_search(run, heard);
      ADD_FAILURE() << name << ": accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(name, 0), 0u) << e.what();
    }
  };
  SearchRun run = small_run(db, 3);
  run.start.medium.grains = 0;
  refused_naming(run, "grains = 0");
  run = small_run(db, -1);
  refused_naming(run, "generations = -1");
  run = small_run(db, 3);
  run.validate_starts = -2;
  refused_naming(run, "validate-starts = -2");
  run = small_run(db, 3);
  run.search.lambda = 0;
  refused_naming(run, "lambda");
  run = small_run(db, 3);
  run.resume = 4;  // no such file yet: refused by the store, naming it
  EXPECT_THROW(run_search(run, heard), DatabaseError);
  run = small_run(db, 3);
  run.start.medium.grains = 400;  // more than the box holds: not a start to retry
  refused_naming(run, "grains = 400");
  run = small_run(db, 3);
  run.start.medium.seed = 1;  // traps the droplet (search_fixtures.hpp)
  run.start.attempts = 1;
  try {
    run_search(run, heard);
    ADD_FAILURE() << "a start through which the droplet does not pass was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("start-attempts = 1: no starting medium let the droplet pass", 0), 0u)
        << e.what();
  }
  EXPECT_EQ(heard.refused, 1);
  EXPECT_FALSE(std::filesystem::exists(db));
  EXPECT_TRUE(heard.started_with.empty());
  // A stored history without that run: refused naming it, the file unchanged.
  run_search(small_run(db, 1), heard);
  const auto size = std::filesystem::file_size(db);
  run = small_run(db, 3);
  run.resume = 4;
  refused_naming(run, "resume = 4");
  EXPECT_EQ(std::filesystem::file_size(db), size);
  std::filesystem::remove(db);
}

TEST(SearchService, IslandsAreRunsOfOneArchipelagoAndResumeTogetherToTheSameBits) {
  const std::string whole = test::fresh_path("search_service_islands.db"),
                    parts = test::fresh_path("search_service_islands_parts.db");
  const auto islands_run = [](const std::string& db) {
    SearchRun r = small_run(db, 5);
    r.search.lambda = 1;
    r.islands = 3;
    r.migrate_every = 2;
    r.migration = "broadcast";
    return r;
  };
  SearchRecorder reference;
  const SearchRunSummary r = run_search(islands_run(whole), reference);
  EXPECT_EQ(reference.island_runs, (std::vector<std::int64_t>{1, 2, 3}));
  EXPECT_TRUE(reference.started_with.empty());   // islands_started instead
  EXPECT_EQ(reference.generations.size(), 15u);  // 5 generations of 3 islands
  EXPECT_EQ(std::count(reference.islands_heard.begin(), reference.islands_heard.end(), 2), 5);
  ASSERT_EQ(r.islands.size(), 3u);
  EXPECT_EQ(r.drive.termination, Termination::generations);
  EXPECT_EQ(r.migration, "broadcast");
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.islands[i].last_generation, 5);
    EXPECT_LE(r.islands[i].best.eval.tortuosity, r.best.eval.tortuosity);
    const RunRecord rec = open_history(whole, OpenMode::read_only)->run(r.islands[i].run);
    EXPECT_EQ(rec.island, static_cast<int>(i));
    EXPECT_EQ(rec.archipelago, 1);
    EXPECT_EQ(rec.status, "finished");
  }
  // Stopped after four generations (of any islands), then resumed from island 2's run: all of
  // them go on, and every island's history is the uninterrupted one's.
  SearchRecorder first;
  first.stop_after = 4;
  const SearchRunSummary s = run_search(islands_run(parts), first);
  EXPECT_EQ(s.drive.termination, Termination::callback);
  SearchRun resume = islands_run(parts);
  resume.resume = 3;
  resume.generations.reset();
  resume.given = {"islands"};  // 3, as stored
  SearchRecorder second;
  const SearchRunSummary t = run_search(resume, second);
  EXPECT_TRUE(t.resumed);
  EXPECT_EQ(second.island_runs, (std::vector<std::int64_t>{1, 2, 3}));
  EXPECT_EQ(t.best.eval.tortuosity, r.best.eval.tortuosity);
  for (std::int64_t run = 1; run <= 3; ++run) EXPECT_EQ(history_bits(parts, run), history_bits(whole, run)) << run;
  // A run of one search is not resumed as islands.
  resume = small_run(whole, 6);
  std::filesystem::remove(parts);
  run_search(small_run(parts, 1), first);
  resume.db = parts;
  resume.resume = 1;
  resume.islands = 2;
  resume.given = {"islands"};
  try {
    run_search(resume, first);
    ADD_FAILURE() << "a run of one search resumed as islands";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--islands 2 (stored nothing)"), std::string::npos) << e.what();
  }
  std::filesystem::remove(whole);
  std::filesystem::remove(parts);
}

TEST(SearchService, AStoredTargetThatIsNotAWholeNumberIsRefusedByOneSearchAndByIslands) {
  for (const int islands : {1, 2}) {
    const std::string db = test::fresh_path("search_service_target.db");
    SearchRun run = small_run(db, 1);
    run.islands = islands;
    SearchRecorder heard;
    run_search(run, heard);
    SQLite::Database(db, SQLite::OPEN_READWRITE)
        .exec(R"(UPDATE runs SET params = json_set(params, '$."target-generations"', 2.5))");
    const auto before = history_bits(db, 1);
    run.resume = 1;
    run.generations.reset();
    try {
      run_search(run, heard);
      ADD_FAILURE() << islands << " island(s): a target of 2.5 was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("run 1: its stored target-generations 2.5 is not a whole number"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(history_bits(db, 1), before);
    std::filesystem::remove(db);
  }
}

TEST(SearchService, AFileThatIsNotAHistoryIsRefusedAndKept) {
  const std::string db = test::fresh_path("search_service_text.db");
  { std::ofstream(db) << "not a database\n"; }
  SearchRecorder heard;
  EXPECT_THROW(run_search(small_run(db, 2), heard), DatabaseError);
  EXPECT_EQ(test::first_line(db), "not a database");
  std::filesystem::remove(db);
}

}  // namespace
}  // namespace softdrop
