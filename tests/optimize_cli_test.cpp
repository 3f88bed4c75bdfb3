// `softdrop optimize / history / export` end to end: a search killed with SIGKILL at random
// instants and resumed each time writes exactly the history of one that never stopped; an exported
// configuration re-simulated gives the stored T bit for bit; two searches share one file.
#include <SQLiteCpp/SQLiteCpp.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "cli_run.hpp"
#include "search_cli.hpp"

namespace {
using softdrop::test::dump;
using softdrop::test::fresh;
using softdrop::test::has_run;
using softdrop::test::kScene;
using softdrop::test::Result;
using softdrop::test::run;
using softdrop::test::spawn;
using softdrop::test::wait_for;

TEST(Optimize, KilledAtRandomInstantsAndResumedEqualsAnUninterruptedRun) {
  // The reference runs one generation at a time; the killed runs speculate on 2 threads.
  const std::string gens = " --generations 30 --lambda 2 --threads 2 ";
  const std::string ref = fresh("ref.db"), killed = fresh("killed.db");
  const Result r = run("optimize --db " + ref + kScene + " --generations 30 --lambda 2 --threads 1");
  ASSERT_EQ(r.code, 0) << r.err;

  std::mt19937 rng(2026);  // the test's kill instants are reproducible too
  int kills = 0, resumes = 0;
  for (int attempt = 0; attempt < 7; ++attempt) {
    const bool resume = has_run(killed);
    resumes += resume;
    const pid_t pid = spawn("optimize --db " + killed + kScene + gens + (resume ? " --resume 1" : ""));
    std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(30, 700)(rng)));
    if (kill(pid, SIGKILL) == 0) ++kills;
    wait_for(pid);
  }
  const std::string last = has_run(killed) ? " --resume 1" : "";
  const Result fin = run("optimize --db " + killed + kScene + gens + last);
  ASSERT_EQ(fin.code, 0) << fin.err;
  EXPECT_GE(kills, 5);
  EXPECT_GE(resumes, 3);
  EXPECT_EQ(dump(killed, 1), dump(ref, 1));
  SQLite::Database db(killed, SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM runs").getInt(), 1);
}

TEST(Optimize, LambdaFourWritesTheSameHistoryOnOneAndTwoThreads) {
  const std::string one = fresh("lambda_t1.db"), two = fresh("lambda_t2.db");
  // The paper's strategy, which evaluates later generations ahead (the speculation counted below).
  const std::string paper = " --strategy paper --relocate-every 0";
  ASSERT_EQ(run("optimize --db " + one + kScene + paper + " --generations 8 --lambda 4 --threads 1").code, 0);
  ASSERT_EQ(run("optimize --db " + two + kScene + paper + " --generations 8 --lambda 4 --threads 2").code, 0);
  const std::string a = dump(one, 1);
  EXPECT_EQ(a, dump(two, 1));
  EXPECT_NE(a.find("|8|33|"), std::string::npos) << "8 generations of 4 candidates plus the start";
  // Lanes set by hand: the same history, and the summary says what ran.
  const std::string three = fresh("lambda_l3.db");
  const Result r = run("optimize --db " + three + kScene + paper +
                       " --generations 8 --lambda 4 --threads 2 --lanes 3 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(dump(three, 1), a);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("speculation").at("threads"), 2);
  EXPECT_EQ(j.at("speculation").at("lanes"), 3);
  // The steps kept are those of the stored candidates of generations 1 to 8.
  SQLite::Database db(three, SQLite::OPEN_READONLY);
  EXPECT_EQ(j.at("speculation").at("kept_steps").get<std::int64_t>(),
            db.execAndGet("SELECT sum(steps) FROM candidates WHERE run_id = 1 AND generation > 0").getInt64());
  EXPECT_GE(j.at("speculation").at("dropped_steps").get<std::int64_t>(),
            j.at("speculation").at("dropped_evaluations").get<std::int64_t>());
}

TEST(Optimize, ExportedGenerationsReproduceTheStoredTBitForBit) {
  const std::string db = fresh("export.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 20").code, 0);
  const Result best = run("history --db " + db + " --run 1 --best --format json");
  ASSERT_EQ(best.code, 0) << best.err;
  const auto curve = nlohmann::json::parse(best.out);
  ASSERT_GE(curve.size(), 2u);
  double previous = 0;
  for (const auto& point : curve) {  // the best-T curve rises strictly
    EXPECT_GT(point["best_tortuosity"].get<double>(), previous);
    previous = point["best_tortuosity"].get<double>();
  }
  for (const auto& point : {curve.front(), curve.back()}) {
    const std::string g = std::to_string(point["generation"].get<int>());
    const std::string grains = fresh("export_" + g + ".json"), config = fresh("export_" + g + ".toml");
    const Result e =
        run("export --db " + db + " --run 1 --generation " + g + " -o " + grains + " --simulate-config " + config);
    ASSERT_EQ(e.code, 0) << e.err;
    const Result s = run("simulate --config " + config + " --format json");
    ASSERT_EQ(s.code, 0) << s.err;
    const auto j = nlohmann::json::parse(s.out);
    EXPECT_EQ(j["run"]["outcome"], "passed");
    EXPECT_EQ(j["run"]["tortuosity"].get<double>(), point["best_tortuosity"].get<double>()) << "generation " << g;
  }
}

TEST(Optimize, ResumeRefusesContradictingOptionsAndNamesThem) {
  const std::string db = fresh("contradict.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3").code, 0);
  const Result r = run("optimize --db " + db + " --resume 1 --generations 5 --lambda 3 --nrt 7e8 --seed 7");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--lambda 3 (stored 8)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--nrt"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("--seed"), std::string::npos) << "the same value is no contradiction: " << r.err;
  const Result missing = run("optimize --db " + db + " --resume 9 --generations 5");
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.err.find("resume = 9: '" + db + "' has no run 9"), std::string::npos) << missing.err;
  // Resuming with the stored options (none given) continues; asking for fewer does nothing.
  EXPECT_EQ(run("optimize --db " + db + " --resume 1 --generations 5 --quiet").code, 0);
  EXPECT_EQ(run("optimize --db " + db + " --resume 1 --generations 4 --quiet").code, 0);
  const auto runs = nlohmann::json::parse(run("history --db " + db + " --format json").out);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["generations"], 5);
  EXPECT_EQ(runs[0]["status"], "finished");
}

TEST(Optimize, TwoSearchesShareOneFileWhileItIsRead) {
  const std::string db = fresh("shared.db"), solo = fresh("solo.db");
  const std::string gens = " --generations 12 ";
  ASSERT_EQ(run("optimize --db " + solo + kScene + gens).code, 0);
  const pid_t a = spawn("optimize --db " + db + kScene + gens);
  const pid_t b = spawn("optimize --db " + db + kScene + gens);
  int reads = 0;
  for (int i = 0; i < 20; ++i) {  // readers see consistent snapshots while both write
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!has_run(db)) continue;
    const Result h = run("history --db " + db + " --format csv");
    EXPECT_EQ(h.code, 0) << h.err;
    reads += h.code == 0;
  }
  EXPECT_EQ(wait_for(a), 0);
  EXPECT_EQ(wait_for(b), 0);
  EXPECT_GT(reads, 0);
  // Both runs are complete, and each equals the same search run alone.
  EXPECT_EQ(dump(db, 1), dump(solo, 1));
  EXPECT_EQ(dump(db, 2), dump(solo, 1));
}

TEST(Optimize, CtrlCFinishesTheGenerationInFlightAndTimeLimitStops) {
  const std::string db = fresh("sigint.db");
  const pid_t pid = spawn("optimize --db " + db + kScene + " --generations 100000 --lambda 2 --threads 1");
  for (int i = 0; i < 200 && !has_run(db); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  EXPECT_EQ(wait_for(pid), 130);
  SQLite::Database h(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(h.execAndGet("SELECT status FROM runs WHERE id = 1").getString(), "interrupted");
  const int last = h.execAndGet("SELECT generations FROM runs WHERE id = 1").getInt();
  EXPECT_GT(last, 0);
  // Every stored generation is whole: its two candidates are there.
  EXPECT_EQ(h.execAndGet("SELECT count(*) FROM candidates WHERE run_id = 1").getInt(), 1 + 2 * last);

  const std::string timed = fresh("timed.db");
  const Result r = run("optimize --db " + timed + kScene + " --generations 100000 --time-limit 0.5 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["termination"], "time-limit");
  EXPECT_GT(j["generations_run"].get<int>(), 0);
  EXPECT_LT(j["generations_run"].get<int>(), 100000);
}

TEST(Optimize, BadOptionsAndFailedStartsLeaveNoDatabase) {
  const std::string db = fresh("never.db");
  for (const std::string args : {"--lambda 0", "--step -1", "--grains -5", "--constraint-order shuffled",
                                 "--grains 100000 --width 100 --height 100", "--time-limit -3", "--lanes 65"}) {
    const Result r = run("optimize --db " + db + " " + args);
    SCOPED_TRACE(args);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("softdrop: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(std::filesystem::exists(db));
  }
}

TEST(Optimize, BadDatabaseFilesGiveOneLineAndStayUnchanged) {
  const std::string text = fresh("cli_text.db");
  std::ofstream(text) << "not a database at all, just some text that is long enough to have a header\n";
  for (const std::string& cmd : {"optimize --db " + text + kScene + " --generations 2", "history --db " + text,
                                 "export --db " + text + " --run 1 -o " + fresh("x.json")}) {
    const Result r = run(cmd);
    SCOPED_TRACE(cmd);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("not an SQLite database"), std::string::npos) << r.err;
  }
  std::ifstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "not a database at all, just some text that is long enough to have a header");
  EXPECT_FALSE(std::filesystem::exists(fresh("x.json")));
  const Result none = run("history --db " + fresh("nothing.db"));
  EXPECT_NE(none.err.find("no such file"), std::string::npos) << none.err;
  EXPECT_FALSE(std::filesystem::exists(fresh("nothing.db")));
}

}  // namespace

namespace {

// A resume without --generations goes on to the run's own target; one at or below the stored
// generation says so and leaves the run alone; the summary counts what the history counts.
TEST(Optimize, ResumeGoesToTheStoredTargetAndSaysWhenThereIsNothingToDo) {
  const std::string db = softdrop::test::fresh("target.db"), ref = softdrop::test::fresh("target_ref.db");
  const Result first = run("optimize --db " + db + kScene + " --generations 4");
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_NE(first.out.find("4 generations, "), std::string::npos) << first.out;
  EXPECT_NE(first.out.find(" 33 evaluations"), std::string::npos) << first.out;  // 4 x 8 and generation 0's
  EXPECT_EQ(first.out.find("speculation"), std::string::npos) << "only with --verbose: " << first.out;
  const Result history = run("history --db " + db + " --format csv");
  EXPECT_NE(history.out.find(",4,33,"), std::string::npos) << history.out;  // generations 4, evaluations 33
  auto status = [&] {
    SQLite::Database d(db, SQLite::OPEN_READONLY);
    return d.execAndGet("SELECT status FROM runs WHERE id = 1").getString();
  };
  // At its target already: nothing to do, with or without a lower --generations.
  for (const std::string more : {"", " --generations 3", " --generations 4"}) {
    SCOPED_TRACE(more);
    const Result again = run("optimize --db " + db + kScene + " --resume 1" + more);
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_NE(again.out.find("nothing to do: run 1 is at generation 4"), std::string::npos) << again.out;
    EXPECT_EQ(status(), "finished");
  }
  // A higher target is stored: the next resume without --generations goes no further, and the
  // run equals one started with that target.
  ASSERT_EQ(run("optimize --db " + db + kScene + " --resume 1 --generations 7").code, 0);
  EXPECT_NE(run("optimize --db " + db + kScene + " --resume 1").out.find("nothing to do: run 1 is at generation 7"),
            std::string::npos);
  const Result verbose = run("optimize --db " + ref + kScene + " --generations 7 --verbose");
  ASSERT_EQ(verbose.code, 0) << verbose.err;
  EXPECT_NE(verbose.out.find("speculation  "), std::string::npos) << verbose.out;
  EXPECT_EQ(dump(db, 1), dump(ref, 1));
  // A run stopped short of its target (here: marked so by hand, as a kill or a time limit leaves it)
  // keeps its status when a resume asks for less, and goes on to its target when asked for nothing.
  {
    SQLite::Database d(db, SQLite::OPEN_READWRITE);
    d.exec("UPDATE runs SET status = 'interrupted', params = json_set(params, '$.\"target-generations\"', 9)");
  }
  const Result less = run("optimize --db " + db + kScene + " --resume 1 --generations 6");
  EXPECT_NE(less.out.find("nothing to do: run 1 is at generation 7 (target 6)"), std::string::npos) << less.out;
  EXPECT_EQ(status(), "interrupted");
  const Result rest = run("optimize --db " + db + kScene + " --resume 1");
  EXPECT_NE(rest.out.find("reached generation 9"), std::string::npos) << rest.out;
  EXPECT_EQ(status(), "finished");
  const Result json = run("optimize --db " + db + kScene + " --resume 1 --format json");
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["termination"], "nothing to do");
  EXPECT_EQ(j["last_generation"], 9);
}

}  // namespace

namespace {

TEST(Optimize, HistoryListsCandidatesAndTheStoredOptions) {
  const std::string db = softdrop::test::fresh("candidates.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3 --lambda 2").code, 0);
  const Result c = run("history --db " + db + " --run 1 --candidates --format csv");
  ASSERT_EQ(c.code, 0) << c.err;
  std::istringstream lines(c.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line,
            "generation,candidate,kind,accepted,outcome,tortuosity,steps,touched,moved_grain,moved,seconds,reason,"
            "droplets,passed");
  int rows = 0, accepted = 0;
  while (std::getline(lines, line)) {
    ++rows;
    accepted += line.find(",1,passed,") != std::string::npos || line.find(",1,stuck,") != std::string::npos;
  }
  EXPECT_EQ(rows, 1 + 3 * 2);  // generation 0's one, then lambda = 2 a generation
  EXPECT_GE(accepted, 1);      // generation 0's candidate is its arrangement
  EXPECT_LE(accepted, 4);      // at most one a generation
  const Result runs = run("history --db " + db + " --format json");
  const nlohmann::json r = nlohmann::json::parse(runs.out);
  EXPECT_EQ(r[0]["evaluations"], rows);
  const Result p = run("history --db " + db + " --run 1 --params --format csv");
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_NE(p.out.find("\nlambda,2\n"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("\ntarget-generations,3\n"), std::string::npos) << p.out;
  // The program's default strategy is the measured best: es with a relocation every third generation.
  EXPECT_NE(p.out.find("\nstrategy,es\n"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("\nrelocate-every,3\n"), std::string::npos) << p.out;
  // ... and ends a candidate at rest without waiting for the stuck test (results/stuck_test/).
  EXPECT_NE(p.out.find("\nrest-window,0.05\n"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("\nrest-distance,0.1\n"), std::string::npos) << p.out;
  for (const std::string bad : {"--candidates", "--params"}) {
    const Result e = run("history --db " + db + " " + bad);
    EXPECT_EQ(e.code, 1);
    EXPECT_NE(e.err.find(bad + " needs --run"), std::string::npos) << e.err;
  }
  EXPECT_EQ(run("history --db " + db + " --run 1 --best --candidates").code, 2);
  EXPECT_NE(run("history --help").out.find("best_candidate_tortuosity = the best among"), std::string::npos);
  // --params in JSON keeps each option's type: numbers as numbers, flags as true or false.
  const nlohmann::json typed = nlohmann::json::parse(run("history --db " + db + " --run 1 --params --format json").out);
  for (const auto& row : typed) {
    if (row["option"] == "lambda") {
      EXPECT_EQ(row["value"], 2);
    } else if (row["option"] == "walls") {
      EXPECT_EQ(row["value"], false);
    } else if (row["option"] == "strategy") {
      EXPECT_EQ(row["value"], "es");
    }
  }
}

// --preset paper is the paper's algorithm spelled out, to the bit; it fills only the options not
// given, and a resume under it checks that the stored run is the paper's.
TEST(Optimize, PresetPaperIsThePapersAlgorithm) {
  const std::string preset = fresh("preset_paper.db"), spelled = fresh("preset_spelled.db");
  ASSERT_EQ(run("optimize --db " + preset + kScene + " --generations 6 --preset paper").code, 0);
  ASSERT_EQ(
      run("optimize --db " + spelled + kScene + " --generations 6 --strategy paper --lambda 1 --relocate-every 0").code,
      0);
  EXPECT_EQ(dump(preset, 1), dump(spelled, 1));
  ASSERT_EQ(run("optimize --db " + preset + kScene + " --generations 2 --preset paper --lambda 2").code, 0);
  const Result p = run("history --db " + preset + " --run 2 --params --format csv");
  EXPECT_NE(p.out.find("\nlambda,2\n"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("\nstrategy,paper\n"), std::string::npos) << p.out;
  EXPECT_EQ(run("optimize --db " + preset + " --resume 1 --preset paper --generations 8").code, 0);
  const std::string plain = fresh("preset_plain.db");
  ASSERT_EQ(run("optimize --db " + plain + kScene + " --generations 2").code, 0);
  const Result r = run("optimize --db " + plain + " --resume 1 --preset paper --generations 4");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("contradicts the stored run: --lambda 1 (stored 8)"), std::string::npos) << r.err;
  EXPECT_EQ(run("optimize --db " + plain + " --preset fast").code, 2);
}

}  // namespace
