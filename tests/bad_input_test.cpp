// Bad values get one line naming the option; signals leave no temporary file behind and end with
// the conventional status; grain files with a byte order mark, binary junk or grains outside the
// box are read or refused the same way by every command.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "search_cli.hpp"
#include "softdrop/medium.hpp"

namespace {
using namespace softdrop::test;

TEST(BadValues, GetOneLineNamingTheOption) {
  const std::string db = fresh("bad_values.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3").code, 0);
  struct Case {
    std::string args, names;
    int code;
  };
  for (const Case& c : {
           Case{"simulate --x0 nan", "--x0: 'nan' is not a finite number", 2},
           Case{"simulate --x0 inf", "--x0: 'inf' is not a finite number", 2},
           Case{"simulate --x0 -1e300", "x0 = -1e+300: the droplet must start inside the box", 1},
           Case{"simulate --walls --x0 600 --width 500",
                "x0 = 600: the droplet must start inside the box, x0 in [8, 492]", 1},
           Case{"render snapshots --times 0.01 -o " + temp_path("s.png") + " --x0 -3", "x0 = -3", 1},
           Case{"optimize --db " + db + " --seed -1", "--seed: '-1' is not a whole number in [0, 2^64 - 1]", 2},
           Case{"optimize --db " + db + " --seed 18446744073709551616", "is more than 2^64 - 1", 2},
           Case{"sweep --db " + db + " --seed 1e3", "--seed: '1e3' is not a whole number", 2},
           Case{"simulate --medium-seed -5", "--medium-seed: '-5'", 2},
           Case{"optimize --db " + db + " --grains 0", "grains = 0: must be >= 1", 1},
           Case{"export --db " + db + " --run 1 --generation -1 -o " + temp_path("e.json"),
                "--generation: '-1' is not a whole number >= 0", 2},
           Case{"render search --db " + db + " --run 1 --generation 999 -o " + temp_path("s.png"),
                "generation = 999: run 1 has stored generations 0 to 3", 1},
           Case{"optimize --db " + db + " --resume 7", "resume = 7: '" + db + "' has no run 7", 1},
       }) {
    SCOPED_TRACE(c.args);
    const Result r = run(c.args);
    EXPECT_EQ(r.code, c.code) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(temp_path("s.png")));
  EXPECT_FALSE(std::filesystem::exists(temp_path("e.json")));
  // The largest seed is a seed.
  EXPECT_EQ(run("--check optimize --db " + db + " --seed 18446744073709551615").code, 0);
}

// --check refuses what the run would refuse later: grains beyond the box's area at once, and
// non-overlapping porosities that random placement jams before reaching, by placing them.
TEST(Check, CatchesGrainCountsAndPorositiesTheRunCannotPlace) {
  const std::string db = fresh("check_place.db");
  struct Case {
    std::string args, says;
  };
  for (const Case& c :
       {Case{"optimize --db " + db + " --grains 100000",
             "grains = 100000: cannot fit in 500 x 500: even the smallest grains (radius 16, gap 0.13) "
             "would need more than the box's area; at most 275"},
        Case{"optimize --db " + db + " --grains 100", "grains = 100: do not fit in the box"},
        Case{"simulate --kind non-overlapping --porosity 0.35 --width 200 --height 200",
             "porosity = 0.35: unreachable for non-overlapping grains"},
        Case{"sweep --db " + db + " --kind non-overlapping --porosities 0.8,0.4 --width 200 --height 200",
             "porosity = 0.4: unreachable"}}) {
    SCOPED_TRACE(c.args);
    const Result r = run("--check " + c.args);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(db));
  EXPECT_EQ(run("--check optimize --db " + db + " --grains 60").code, 0);
  EXPECT_EQ(run("--check simulate --kind non-overlapping --porosity 0.75").code, 0);
  EXPECT_FALSE(std::filesystem::exists(db));  // a check writes nothing
}

// --check refuses a database the run would refuse: here, one in a folder that does not exist.
TEST(Check, RefusesTheDatabaseTheRunWouldRefuse) {
  for (const std::string command : {"optimize", "sweep"}) {
    const Result r = run("--check " + command + " --db /nonexistent/x.db");
    EXPECT_EQ(r.code, 1) << command;
    EXPECT_NE(r.err.find("--db '/nonexistent/x.db': folder '/nonexistent' does not exist"), std::string::npos) << r.err;
  }
}

// --check render paths applies the run's own limits: the memory of the paths in flight (a thread's
// lanes of droplets, each up to --max-steps), or a droplet count out of range, is refused without
// drawing; a count it takes passes, however many droplets (a finished path keeps only what is drawn).
TEST(Check, RefusesThePathsPictureTheRunWouldRefuse) {
  const std::string out = fresh_path("check_paths.png");
  const Result big = run("--check render paths --droplets 3000 --threads 1 --max-steps 1000000000 -o " + out);
  EXPECT_EQ(big.code, 1);
  EXPECT_NE(big.err.find("path-interval = 50: "), std::string::npos) << big.err;
  EXPECT_NE(big.err.find("droplets of up to 1000000000 steps could keep"), std::string::npos) << big.err;
  EXPECT_EQ(run("--check render paths --droplets 0 -o " + out).code, 1);
  EXPECT_EQ(run("--check render paths --droplets 30 --path-interval 0 -o " + out).code, 1);
  for (const std::string droplets : {"30", "3000", "1000000"}) {
    const Result fine = run("--check render paths --droplets " + droplets + " -o " + out);
    EXPECT_EQ(fine.code, 0) << droplets << ": " << fine.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(BadWords, MistypedOptionsAndCommandsGetTheNearestName) {
  struct Case {
    std::string args, says;
  };
  for (const Case& c : {
           Case{"simulate --porosty 0.5", "unknown option '--porosty' (did you mean --porosity?)"},
           Case{"simulate --porosity=0.5 --thread 2", "unknown option '--thread' (did you mean --threads?)"},
           Case{"optimize --lamda 2", "unknown option '--lamda' (did you mean --lambda?)"},
           Case{"render paths --droplet-color 102030", "(did you mean --droplet-colour?)"},
           Case{"simulat --x0 3", "unknown command 'simulat' (did you mean simulate?)"},
           Case{"render medum -o m.png", "unknown command 'medum' of render (did you mean medium?)"},
           Case{"sweep-reprot --db x.db", "(did you mean sweep-report?)"},
           // Nothing close: the parser's own message.
           Case{"simulate --frobnicate", "not expected: --frobnicate"},
       }) {
    SCOPED_TRACE(c.args);
    const Result r = run(c.args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

// Starts a command, waits until its temporary output file appears, then sends `sig`.
int signal_while_writing(const std::string& args, const std::string& output, int sig) {
  const pid_t pid = spawn(args);
  const std::string tmp = output + ".tmp." + std::to_string(pid);
  for (int i = 0; i < 3000 && !std::filesystem::exists(tmp); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(std::filesystem::exists(tmp)) << "the output was never being written";
  kill(pid, sig);
  const int code = wait_for(pid);
  EXPECT_FALSE(std::filesystem::exists(tmp));
  EXPECT_FALSE(std::filesystem::exists(output));
  return code;
}

TEST(Signals, LeaveNoTemporaryFileAndEndWithTheConventionalStatus) {
  const std::string gif = fresh("signal.gif");
  // An animation writes its frames into the temporary file for about a second.
  const std::string args = "render animation --size 600 -o " + gif;
  EXPECT_EQ(signal_while_writing(args, gif, SIGINT), -SIGINT);
  EXPECT_EQ(signal_while_writing(args, gif, SIGTERM), -SIGTERM);
  EXPECT_EQ(signal_while_writing(args, gif, SIGHUP), -SIGHUP);
  // A search stops after the generation in flight, status 128 + the signal.
  const std::string db = fresh("signal.db");
  const pid_t pid = spawn("optimize --db " + db + kScene + " --generations 100000");
  for (int i = 0; i < 2000 && committed_generations(db) < 1; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGTERM);
  EXPECT_EQ(wait_for(pid), 143);
}

// simulate stops starting droplets at the first signal, lets those in flight finish, and writes
// them: droplets 0 to n - 1, the rows an uninterrupted run of n droplets has, to the bit.
TEST(Signals, AStoppedSimulateWritesTheDropletsThatRan) {
  const std::string runs = fresh("stopped_runs.csv"), err = fresh("stopped.err"), ref = fresh("ref_runs.csv");
  const pid_t pid = spawn("simulate --droplets 5000 --seed 3 --runs " + runs, err);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGTERM);
  EXPECT_EQ(wait_for(pid), 143);
  std::ifstream e(err);
  const std::string said((std::istreambuf_iterator<char>(e)), std::istreambuf_iterator<char>());
  const auto at = said.find("simulate: stopped by a signal after ");
  ASSERT_NE(at, std::string::npos) << said;
  const int n = std::stoi(said.substr(at + 36));
  EXPECT_GT(n, 0);
  EXPECT_LT(n, 5000);
  EXPECT_NE(said.find(" of 5000 droplets; the outputs hold those " + std::to_string(n)), std::string::npos) << said;
  ASSERT_EQ(run("simulate --droplets " + std::to_string(n) + " --seed 3 --quiet --runs " + ref).code, 0);
  std::ifstream a(runs), b(ref);
  const std::string mine((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>()),
      theirs((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_EQ(mine, theirs);
  EXPECT_EQ(std::count(mine.begin(), mine.end(), '\n'), n + 1);  // the header and a row a droplet
}

softdrop::Medium read_csv(const std::string& text) {
  std::istringstream in(text);
  return softdrop::read_medium(in, softdrop::GrainFileFormat::csv, "m.csv");
}

std::string refusal(const std::string& text) {
  try {
    read_csv(text);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "accepted";
}

TEST(GrainFiles, ByteOrderMarkJunkAndGrainsOutsideTheBox) {
  const std::string body = "# width=100\n# height=50\nx,y,r\n40,25,3\n";
  EXPECT_EQ(read_csv("\xEF\xBB\xBF" + body).grains.size(), 1u);
  EXPECT_EQ(refusal("# width=100\n# height=50\nx,y,r\n4\x01\xff,25,3\n"),
            "grain file 'm.csv': line 4: '4\\x01\\xff' is not a number");
  EXPECT_EQ(refusal("\x80\x81z\n"),
            "grain file 'm.csv': line 1: expected header x,y,r,width,height,periodic (or x,y,r), got '\\x80\\x81z'");
  // A grain reaching into the box is a grain of the medium; one wholly above or below is refused.
  EXPECT_EQ(read_csv("# width=100\n# height=50\nx,y,r\n40,52,3\n40,-2,3\n").grains.size(), 2u);
  for (const std::string y : {"53.5", "-3", "1e300"}) {
    SCOPED_TRACE(y);
    EXPECT_NE(refusal("# width=100\n# height=50\nx,y,r\n40," + y + ",3\n").find("lies wholly outside the box in y"),
              std::string::npos);
  }
  // simulate and optimize agree on a grain above the box.
  const std::string file = fresh("above.csv");
  std::ofstream(file) << "# width=100\n# height=50\nx,y,r\n40,25,3\n60,80,3\n";
  const Result sim = run("simulate --medium " + file);
  const Result opt = run("optimize --db " + fresh("above.db") + " --medium " + file + " --quiet");
  for (const Result& r : {sim, opt}) {
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("grain 1: centre y = 80 with radius 3 lies wholly outside the box"), std::string::npos)
        << r.err;
  }
}

}  // namespace
