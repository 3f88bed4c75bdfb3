// Hardening: absurd values are refused before any large allocation, damaged files (grain files,
// histories) give one line naming the file and the problem, and --check validates without running.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "search_cli.hpp"
#include "softdrop/medium.hpp"
#include "studies/fit.hpp"

namespace {
using namespace softdrop::test;

// Runs softdrop with its address space capped at 1 GiB, so a large allocation before the refusal
// would fail the run with bad_alloc instead of the expected message. (AddressSanitizer reserves
// terabytes of shadow memory, so the sanitizer build runs without the cap.)
Result run_capped(const std::string& args) {
  if (kAddressSanitizer) return run(args);
  return run_shell("ulimit -v 1048576; " + std::string(SOFTDROP_CLI) + " " + args);
}

void expect_one_line_naming(const Result& r, const std::string& names) {
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("softdrop: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
}

TEST(Limits, AbsurdValuesAreRefusedBeforeAnyLargeAllocation) {
  const std::string huge_file = temp_path("huge.csv");
  {  // a 1 GiB grain file (sparse: it takes no disk space)
    std::ofstream(huge_file) << "# width=100\n";
    std::filesystem::resize_file(huge_file, std::uintmax_t{1} << 30);
  }
  const std::string db = fresh("limits.db"), runs = fresh("limits_runs.csv");
  struct Case {
    std::string args, names;
  };
  for (const Case& c : {
           Case{"optimize --db " + db + " --grains 1000000000", "grains = 1000000000"},
           Case{"simulate --masses 100000000", "masses = 100000000"},
           Case{"simulate --dt 1e300", "dt = 1"},
           Case{"simulate --medium " + huge_file, "1024 MiB, more than the limit of 256 MiB"},
           Case{"simulate --width 1e6 --height 1e6", "more than the limit of 1e7"},
           Case{"simulate --width 1e12 --height 1e12", "width = 1e+12: must be in (0, 1e9]"},
           Case{"simulate --width 1e300 --height 1e-300", "width"},
           Case{"simulate --width 100 --height 1e-300", "height"},
           Case{"sweep --db " + db + " --media 1000000000 --droplets 1000000000", "media = 1000000000"},
           Case{"optimize --db " + db + " --lambda 1000000000", "lambda = 1000000000"},
           Case{"simulate --threads 100000", "threads = 100000"},
           Case{"simulate --droplets 100000 --paths " + runs + " --path-interval 1", "path-interval = 1"},
           Case{"simulate --snapshots " + runs + " --droplets 1000000 --masses 100000 --snapshot-times 1,2",
                "snapshot-times"},
           Case{"render paths --output " + temp_path("p.png") + " --droplets 1000000 --max-steps 1000000000",
                "path-interval = 50"},
       }) {
    SCOPED_TRACE(c.args);
    expect_one_line_naming(run_capped(c.args), c.names);
    EXPECT_FALSE(std::filesystem::exists(db));
    EXPECT_FALSE(std::filesystem::exists(runs));
  }
  std::filesystem::remove(huge_file);
}

TEST(GrainFileLimits, TooLargeIsRefusedBeforeReadingAndMistypedFieldsNameTheFile) {
  const std::string big = temp_path("big.json");
  std::ofstream(big) << "{";
  std::filesystem::resize_file(big, softdrop::kMaxGrainFileBytes + 1);
  EXPECT_THROW(
      {
        try {
          softdrop::load_medium(big);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("grain file '" + big + "': 256 MiB, more than the limit"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      std::runtime_error);
  std::filesystem::remove(big);

  for (const std::string text : {R"({"format": 5, "version": 1})", R"({"format": "softdrop-medium", "version": "1"})",
                                 R"({"format": "softdrop-medium", "version": 1, "width": "wide"})"}) {
    std::istringstream in(text);
    try {
      softdrop::read_medium(in, softdrop::GrainFileFormat::json, "m.json");
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("grain file 'm.json': ", 0), 0u) << e.what();
    }
  }
}

TEST(GrainFileLimits, PeriodicCentresMustLieInTheBox) {
  for (const std::string x : {"-0.5", "100.5", "1e300"}) {
    std::istringstream in("# width=100\n# height=50\n# periodic=true\nx,y,r\n" + x + ",25,3\n");
    try {
      softdrop::read_medium(in, softdrop::GrainFileFormat::csv, "m.csv");
      ADD_FAILURE() << x << " was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("must be in [0, width]"), std::string::npos) << e.what();
    }
  }
  std::istringstream edge("# width=100\n# height=50\n# periodic=true\nx,y,r\n0,25,3\n100,25,3\n");
  EXPECT_EQ(softdrop::read_medium(edge, softdrop::GrainFileFormat::csv, "m.csv").grains.size(), 2u);
}

TEST(FitPointsFile, BadLinesAndTooManyPointsNameTheFileAndLine) {
  std::istringstream good("# comment\nphi,t,se\n0.5,1.5,0.02\n0.9,1.1,0.01\n");
  bool used_errors = true;
  const auto points = softdrop::read_fit_points(good, "p.csv", softdrop::FitErrors::media, &used_errors);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_FALSE(used_errors);  // a phi,t,se file brings its own
  EXPECT_EQ(points[1].phi, 0.9);
  EXPECT_EQ(points[1].se, 0.01);
  struct Case {
    std::string text, message;
  };
  for (const Case& c :
       {Case{"x,y\n", "--points 'p.csv' line 1: expected the header"},
        Case{"phi,t,se\n0.5;1.5;0.1\n", "--points 'p.csv' line 2: expected 3 fields, as the header"},
        Case{"phi,t,se\n0.5,1.5x,0.1\n", "line 2: expected numbers for porosity, tortuosity and standard_error"},
        Case{"phi,t,se\n0.5,1.5\n", "line 2: expected 3 fields"}}) {
    std::istringstream in(c.text);
    try {
      softdrop::read_fit_points(in, "p.csv");
      ADD_FAILURE() << c.text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
  std::string many = "phi,t,se\n";
  for (std::size_t i = 0; i <= softdrop::kMaxFitPoints; ++i) many += "0.5,1.5,0.1\n";
  std::istringstream in(many);
  EXPECT_THROW(softdrop::read_fit_points(in, "p.csv"), std::runtime_error);
}

TEST(FitPointsFile, ASweepReportGivesTheChosenErrorAndAnOlderOneSaysWhichToChoose) {
  const std::string report =
      "target_phi,phi,media,droplets,passed,mean_t,standard_error,media_passed,media_standard_"
      "error,stuck_fraction\n"
      "0.5,0.49,10,200,1,1.6,,1,,0.99\n"  // one droplet passed: no error of either kind, not a
                                          // point
      "0.6,0.59,10,200,60,1.5,0.02,7,0.03,0.7\n"
      "0.8,0.79,10,200,150,1.3,0.01,10,0.017,0.25\n";
  std::istringstream media(report), droplets(report);
  const auto m = softdrop::read_fit_points(media, "r.csv");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].phi, 0.59);
  EXPECT_EQ(m[0].t, 1.5);
  EXPECT_EQ(m[0].se, 0.03);
  EXPECT_EQ(m[1].se, 0.017);
  bool used_errors = false;
  const auto d = softdrop::read_fit_points(droplets, "r.csv", softdrop::FitErrors::droplets, &used_errors);
  EXPECT_TRUE(used_errors);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].se, 0.02);
  EXPECT_EQ(d[1].se, 0.01);
  std::istringstream older(
      "target_phi,phi,media,droplets,passed,mean_t,standard_error,stuck_fraction\n"
      "0.6,0.59,10,200,60,1.5,0.02,0.7\n");
  try {
    softdrop::read_fit_points(older, "old.csv");
    ADD_FAILURE() << "an older report was fitted with errors it does not have";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--points 'old.csv' line 1: no media_standard_error column"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--errors droplets"), std::string::npos) << e.what();
  }
}

TEST(FitFailures, PowerLawRunningToTheLogLawIsFittedAndFlagged) {
  // Found by fuzz_fit_points: on these points L-BFGS ended with NLopt's generic failure, so
  // `softdrop fit` printed only "nlopt failure". The best power law lies at b -> 0.
  const std::vector<softdrop::FitPoint> points{{0.45, 1.62, 0.02}, {0.5, 1.51, 0.018}, {0.6, 1.35, 0.015},
                                               {0.7, 1.22, 0.01},  {0.8, 1.14, 0.008}, {0.9, 1.07, 0.005}};
  const softdrop::FitResult power = softdrop::fit_law(softdrop::FitLaw::power, points);
  const softdrop::FitResult log = softdrop::fit_law(softdrop::FitLaw::log, points);
  EXPECT_NE(power.warning.find("b = "), std::string::npos) << power.message;
  EXPECT_TRUE(log.warning.empty());
  EXPECT_LT(std::abs(power.values[1]), 1e-3);
  // The limit (a - c) - c b ln(phi) has a free intercept, so it fits at least as well as the log law.
  EXPECT_LE(power.chi2, log.chi2);
  EXPECT_TRUE(std::isfinite(power.values[0] - power.values[2]));
  EXPECT_GT(power.values[2] * power.values[1], 0.5);  // the slope of T against -ln(phi)
  EXPECT_LT(power.values[2] * power.values[1], 1.0);
}

TEST(DamagedHistory, EditedValuesAreRefusedNamingTheFileAndNothingIsExported) {
  const std::string seed = fresh("damaged_seed.db");
  ASSERT_EQ(run("optimize --db " + seed + kScene + " --generations 3").code, 0);
  struct Case {
    std::string sql, names;
  };
  for (const Case& c : {
           Case{"UPDATE grains SET x = 'left' WHERE grain = 2", "column x holds text, expected a number"},
           Case{"UPDATE grains SET r = -1 WHERE grain = 3", "grain 3: radius -1"},
           Case{"UPDATE grains SET x = 1e300 WHERE grain = 3", "grain 3: centre x"},
           Case{"UPDATE candidates SET tortuosity = NULL", "column tortuosity holds NULL"},
           Case{"UPDATE candidates SET tortuosity = -2", "is not a tortuosity"},
           Case{"DELETE FROM grains WHERE grain = 5", "grain numbering has a hole"},
           Case{"UPDATE runs SET grains = 1000000000000", "the run has 1000000000000"},
           Case{"UPDATE runs SET width = x'00'", "column width holds a blob"},
       }) {
    SCOPED_TRACE(c.sql);
    const std::string db = fresh("damaged.db"), out = fresh("damaged_best.json");
    std::filesystem::copy_file(seed, db);
    {
      SQLite::Database w(db, SQLite::OPEN_READWRITE);
      w.exec(c.sql);
    }
    const Result r = run("export --db " + db + " --run 1 -o " + out);
    expect_one_line_naming(r, "'" + db + "': ");
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    const Result resume = run("optimize --db " + db + " --resume 1 --generations 5 --quiet");
    EXPECT_EQ(resume.code, 1) << resume.err;
    EXPECT_NE(resume.err.find(db), std::string::npos) << resume.err;
  }
}

TEST(DamagedHistory, AHotRollbackJournalIsRolledBackNotRefused) {
  // Found by the soak test under CI load: a process killed inside a transaction of a database in
  // rollback-journal mode (as a new file is before it switches to WAL, or a file edited with
  // sqlite3) leaves a hot journal. The read-only check could not roll it back and refused the
  // file as "unreadable or corrupted", so the next --resume failed.
  const std::string db = fresh("hot.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 2").code, 0);
  {
    SQLite::Database w(db, SQLite::OPEN_READWRITE);
    w.exec("PRAGMA journal_mode = DELETE");
  }
  const std::string before = dump(db, 1);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // dies inside a transaction whose changes already reached the file
    sqlite3* c = nullptr;
    sqlite3_open(db.c_str(), &c);
    sqlite3_exec(c, "PRAGMA cache_size = 1; BEGIN; UPDATE grains SET x = x / 2; UPDATE paths SET y = 0;", nullptr,
                 nullptr, nullptr);
    _exit(0);
  }
  ASSERT_EQ(wait_for(child), 0);
  ASSERT_TRUE(std::filesystem::exists(db + "-journal"));
  const Result r = run("history --db " + db);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(dump(db, 1), before);
  EXPECT_EQ(run("optimize --db " + db + " --resume 1 --generations 4 --quiet").code, 0);
}

TEST(CheckFlag, ValidatesTheOptionsWithoutRunningOrWriting) {
  const std::string runs = fresh("check_runs.csv"), db = fresh("check.db");
  Result r = run("--check simulate --porosity 0.7 --runs " + runs);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(std::filesystem::exists(runs));
  r = run("--check optimize --db " + db + kScene);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(db));
  r = run("--check simulate --porosity 1.7");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("porosity = 1.7"), std::string::npos) << r.err;
  r = run("--check sweep --db " + db + " --shard 3/2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("shard = '3/2'"), std::string::npos) << r.err;
}

}  // namespace
