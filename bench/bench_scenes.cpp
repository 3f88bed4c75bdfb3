// Scene benchmarks: whole runs, timed over repeats (minimum and median), written as CSV with the
// machine and compiler.
//
//   build/bench/bench_scenes [--scene NAME[,NAME...]|all] [--repeats 5] [--threads N] [--lanes N]
//                            [--width W] [--droplet defaults|balloon|explicit|exponential] [--out FILE.csv]
//
// --droplet balloon runs every scene with the balloon (DropletParams::balloon()) on its grains
// (radii 8 to 16) and its default search scene (60 grains in 300 x 300), to compare with the
// defaults (grains of radii 16 to 48, 20 grains in 500 x 500) in one run. --droplet explicit runs
// them with DropletParams::explicit_step() (the defaults' droplet, explicit viscosity step, dt
// / 1.7), --droplet exponential with DropletParams::exponential_step() (the exponential step's
// calibration, at the defaults' dt).
//
// Scenes: free-fall (40 masses, empty box); medium-200 (40 masses through an overlapping medium of
// about 200 grains at phi 0.7); medium-5000 (the same grain density in a 25x larger box, about
// 5000 grains); medium-200-red-black (medium-200 with the red-black constraint order); batch
// (`simulate --droplets 24` on the medium-200 medium: one droplet at a time on 1 thread, the
// default lanes stepped together (24 with AVX-512 or AVX, 1 with SSE2) on 1 thread, and on all
// threads);
// sweep and sweep-long (16 and 64 droplets through each of 4 media, on 1 thread and on all; the
// paper's sweep has 200 per medium); search-l1 and search-l2 (the paper's search at lambda 1 and 2,
// on 1 thread and on all threads with speculation, as `optimize` runs it: 120 and 60 generations);
// search-l2-long (the same at lambda 2 over 400 generations, where the acceptances thin out and the
// end of the run weighs less); search-*-red-black (the same searches with the red-black constraint
// order: other histories, so compare their steps per second); search-es-l8 and search-es-l8-long
// (es, lambda 8, a relocation every third generation, with the paper's single droplet; 15 and 200
// generations); search-mean (the program's default search: the same with the mean objective over
// 16 droplets, 15 generations of 144 droplets, as scripts/run.sh runs 200). Every scene ends its droplets with the
// default exit tests, the rest test among them. --lanes sets the search scenes' lanes (0: the
// default). --width uses at most that vector width (8: AVX-512, 4: AVX, 2: SSE2, 1: scalar), to
// time what a processor without AVX-512 runs. The last column, dropped_steps_per_kept, is a
// speculating search's cost: the steps its dropped evaluations had taken, over the steps counted
// (the kept evaluations'). two-droplets-079-1thread runs 24 pairs (simulate --second-droplet
// distance) through a non-overlapping medium at phi 0.79, one pair at a time, and
// one-droplet-079-1thread the same 24 first droplets alone: the ratio of their seconds is what a
// second droplet costs. two-droplets-079-batch-1thread and one-droplet-079-batch-1thread do the
// same for 48 as batches on one thread (run_two_droplet_batch, run_batch): 24 droplets stepped
// together, or pairs as many as fill those 24 lanes, their rings as lanes of one block. medium-200-image and
// batch-1thread-image run medium-200 and batch-1thread on the same medium drawn as an image at 4 pixels a length unit
// (2000 x 2000 pixels), whose solid the droplets meet through its distance field.
#include <sys/resource.h>
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_media.hpp"
#include "sim/lane_policy.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/search.hpp"
#include "softdrop/simulation.hpp"
#include "softdrop/sweep.hpp"
#include "studies/pore_tortuosity.hpp"

namespace {
using namespace softdrop;
using Clock = std::chrono::steady_clock;

// What one repeat did: work done (steps, mass updates, droplets, evaluations) in `seconds`.
struct Work {
  double seconds = 0, steps = 0, mass_updates = 0, droplets = 0, evaluations = 0;
  long grains = 0;
  double dropped_steps = 0;  // a speculating search's, thrown away (not in steps)
};

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// --droplet: the droplet of every scene, and the grain radii of its media.
DropletParams scene_droplet;
double r_min = MediumOptions{}.r_min, r_max = MediumOptions{}.r_max;
std::string droplet_name = "defaults";
bool balloon() { return droplet_name == "balloon"; }

// Steps of one droplet, re-dropped from a new x every 20 000 steps so that every step is in the
// medium (as bench_step does); `steps` in total.
Work stepping(const Medium& medium, std::int64_t steps, ConstraintOrder order = ConstraintOrder::sequential) {
  DropletParams p = scene_droplet;
  p.constraint_order = order;
  Simulation sim(p, medium);
  double x0 = 37;
  sim.place_above(x0);
  const auto t0 = Clock::now();
  for (std::int64_t i = 1; i <= steps; ++i) {
    sim.step();
    if (i % 20000 == 0) {
      x0 = x0 + 97 > medium.width ? x0 + 97 - medium.width : x0 + 97;
      sim.place_above(x0);
    }
  }
  Work w;
  w.seconds = since(t0);
  w.steps = static_cast<double>(steps);
  w.mass_updates = w.steps * p.masses;
  w.grains = static_cast<long>(medium.grains.size());
  return w;
}

Work free_fall() {
  Medium empty{500, 1'000'000, true, {}, nullptr};  // tall enough for 400 000 steps of free fall
  const DropletParams p = scene_droplet;
  Simulation sim(p, empty);
  sim.place(250, 999'000);
  const std::int64_t steps = 400'000;
  const auto t0 = Clock::now();
  for (std::int64_t i = 0; i < steps; ++i) sim.step();
  Work w;
  w.seconds = since(t0);
  w.steps = static_cast<double>(steps);
  w.mass_updates = w.steps * p.masses;
  return w;
}

// `simulate --droplets 24` on the medium-200 medium: whole runs, `lanes` droplets stepped together
// on each thread (run_interleaved).
Work batch(const Medium& medium, int threads, int lanes) {
  const DropletParams p = scene_droplet;
  BatchOptions b;
  b.droplets = 24;
  b.threads = threads;
  b.lanes = lanes;
  const auto t0 = Clock::now();
  const std::vector<RunSummary> runs = run_batch(p, medium, RunOptions{}, b);
  Work w;
  w.seconds = since(t0);
  for (const RunSummary& r : runs) w.steps += static_cast<double>(r.steps), ++w.droplets;
  w.mass_updates = w.steps * p.masses;
  w.grains = static_cast<long>(medium.grains.size());
  return w;
}

// 2 porosities x 2 media x `per_medium` droplets, as `softdrop sweep` runs them.
Work sweep(int threads, int per_medium) {
  SweepOptions o;
  o.porosities = {0.75, 0.9};
  o.media = 2;
  o.droplets = per_medium;
  o.medium.width = o.medium.height = 300;
  o.medium.r_min = r_min, o.medium.r_max = r_max;
  o.droplet = scene_droplet;
  o.stream = MediaStream::calibration;  // the media every committed sweep scene was timed on
  Work w;
  const auto t0 = Clock::now();
  run_sweep_units(o, sweep_units(o), threads, [&](SweepMedium&& m) {  // as `softdrop sweep` runs
    w.droplets += static_cast<double>(m.droplets.size());
    for (const SweepDroplet& d : m.droplets) w.steps += static_cast<double>(d.steps);
  });
  w.seconds = since(t0);
  w.mass_updates = w.steps * o.droplet.masses;
  return w;
}

// The two-droplet study's scene: `pairs` pairs through a non-overlapping medium at phi 0.79 (the
// second released 40 below the first's start), or, alone, the same first droplets one at a time,
// on one thread: what a second droplet costs (its steps and the ring-ring stages).
Work two_droplets(const Medium& medium, int pairs, bool alone) {
  const DropletParams p = scene_droplet;
  Work w;
  const auto t0 = Clock::now();
  for (int i = 0; i < pairs; ++i) {
    const double x0 = medium.width * (i + 0.5) / pairs;
    if (alone) {
      w.steps += static_cast<double>(Simulation(p, medium).run(x0, RunOptions{}).steps);
      ++w.droplets;
    } else {
      const TwoDropletSummary s = run_two_droplets(p, medium, x0, RunOptions{}, SecondDroplet{});
      w.steps += static_cast<double>(s.first.steps + s.second.steps);
      w.droplets += 2;
    }
  }
  w.seconds = since(t0);
  w.mass_updates = w.steps * p.masses;
  w.grains = static_cast<long>(medium.grains.size());
  return w;
}

// The two-droplet scene as batches on one thread, in the default 24 lanes: `pairs` pairs, a lane a
// droplet, or their first droplets alone.
Work two_droplet_batch(const Medium& medium, int pairs, bool alone) {
  const DropletParams p = scene_droplet;
  BatchOptions b;
  b.droplets = pairs;
  b.threads = 1;
  Work w;
  const auto t0 = Clock::now();
  if (alone) {
    for (const RunSummary& s : run_batch(p, medium, RunOptions{}, b)) w.steps += static_cast<double>(s.steps);
    w.droplets = pairs;
  } else {
    for (const TwoDropletSummary& s : run_two_droplet_batch(p, medium, RunOptions{}, b, SecondDroplet{}))
      w.steps += static_cast<double>(s.first.steps + s.second.steps);
    w.droplets = 2 * pairs;
  }
  w.seconds = since(t0);
  w.mass_updates = w.steps * p.masses;
  w.grains = static_cast<long>(medium.grains.size());
  return w;
}

// The default search: 120 evaluations (120 / lambda generations), or `generations` of them.
int search_lanes = 0;  // --lanes: DriveOptions::lanes of the search scenes (0: its default)

// `es`: the program's default strategy (es with a relocation every third generation) instead of
// the paper's; `starts` > 0: the mean objective over that many droplets (the program's default
// search with es and 16) instead of the paper's single droplet.
Work search(int lambda, int threads, int generations = 0, ConstraintOrder order = ConstraintOrder::sequential,
            bool es = false, int starts = 0) {
  SearchOptions o;
  o.lambda = lambda;
  if (starts > 0) o.objective.kind = ObjectiveKind::mean, o.objective.starts = starts;
  o.droplet = scene_droplet;
  o.droplet.constraint_order = order;
  if (es) {  // as `softdrop optimize` sets its defaults (OptimizeArgs)
    o.strategy.kind = StrategyKind::es;
    o.relocate_every = 3;
  }
  MediumOptions mo;  // optimize's default scene (OptimizeArgs), or the balloon's
  mo.kind = MediumKind::non_overlapping;
  mo.grains = 20;
  if (balloon()) mo.grains = 60, mo.width = mo.height = 300, mo.r_min = r_min, mo.r_max = r_max;
  Configuration best;
  for (mo.seed = 1;; ++mo.seed) {  // the first medium whose droplet passes, as optimize does
    try {
      initial_generation(generate_medium(mo), o, &best);
      break;
    } catch (const std::runtime_error&) {
    }
  }
  Search s(o, best, 0);
  Work w;
  DriveOptions d;
  d.generations = generations > 0 ? generations : 120 / lambda;
  d.lanes = search_lanes;
  d.threads = threads;  // as optimize does: with 2 threads, idle ones speculate on later generations
  const auto t0 = Clock::now();
  const SearchSummary sum = drive(s, d, [&](const Generation& gen, const Configuration&) {
    for (const Candidate& c : gen.candidates) {
      w.steps += static_cast<double>(c.eval.steps), ++w.evaluations;
      w.droplets += c.eval.droplets;
    }
    w.steps += static_cast<double>(gen.parent.steps);  // a robust objective's re-run of the parent
    w.droplets += gen.parent.droplets;
    return true;
  });
  w.seconds = since(t0);
  w.dropped_steps = static_cast<double>(sum.speculation.dropped_steps);
  w.mass_updates = w.steps * o.droplet.masses;
  return w;
}

// The CPU as /proc/cpuinfo names it, with its family and model (a virtual machine may name
// different processors alike: "AMD EPYC" has been a Zen 3 and a Zen 5 here), its vector
// extensions that the step can use, and the kernel.
std::string machine() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU", family, number, flags;
  auto value = [&] { return line.substr(line.find(':') + 2); };
  while (std::getline(cpu, line) && !line.empty()) {  // the first processor's entries
    if (line.rfind("model name", 0) == 0)
      model = value();
    else if (line.rfind("cpu family", 0) == 0)
      family = value();
    else if (line.rfind("model", 0) == 0 && line.find(':') != std::string::npos)
      number = value();
    else if (line.rfind("flags", 0) == 0)
      flags = value();
  }
  std::ostringstream s;
  s << model;
  if (!family.empty()) s << " (family " << family << ", model " << number << ")";
  std::set<std::string> has;
  std::istringstream words(flags);
  for (std::string w; words >> w;) has.insert(w);
  std::string vector = "SSE2";
  for (const char* f : {"avx512f", "avx2", "avx"})  // widest first
    if (has.count(f)) {
      vector = f;
      break;
    }
  utsname u{};
  uname(&u);
  s << ", " << std::thread::hardware_concurrency() << " hardware threads, widest vector extension " << vector << ", "
    << u.sysname << " " << u.release;
  return s.str();
}

double peak_rss_mb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_maxrss) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = "all", out;
  int repeats = 5, threads = static_cast<int>(std::thread::hardware_concurrency()), width = 8;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "bench_scenes: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--scene")
      scene = value();
    else if (a == "--repeats")
      repeats = std::stoi(value());
    else if (a == "--threads")
      threads = std::stoi(value());
    else if (a == "--out")
      out = value();
    else if (a == "--lanes")
      search_lanes = std::stoi(value());
    else if (a == "--width")
      width = std::stoi(value());
    else if (a == "--droplet") {
      const std::string d = value();
      if (d != "defaults" && d != "balloon" && d != "explicit" && d != "exponential") {
        std::cerr << "bench_scenes: --droplet " << d << ": must be defaults, balloon, explicit or exponential\n";
        return 2;
      }
      droplet_name = d;
    } else {
      std::cerr << "bench_scenes: unknown option " << a << "\n";
      return 2;
    }
  }
  if (repeats < 1 || threads < 1 || search_lanes < 0) {
    std::cerr << "bench_scenes: --repeats and --threads must be >= 1, --lanes >= 0\n";
    return 2;
  }
  if (width != 1 && width != 2 && width != 4 && width != 8) {
    std::cerr << "bench_scenes: --width " << width << ": must be 1, 2, 4 or 8\n";
    return 2;
  }
  limit_constraint_vector_width(static_cast<VectorWidth>(width));
  if (balloon()) scene_droplet = DropletParams::balloon(), r_min = 8, r_max = 16;
  if (droplet_name == "explicit") scene_droplet = DropletParams::explicit_step();
  if (droplet_name == "exponential") scene_droplet = DropletParams::exponential_step();
  const Medium m200 = bench::medium_200(500, r_min, r_max), m5000 = bench::medium_200(2500, r_min, r_max);
  MediumOptions pair_options;  // the two-droplet study's case
  pair_options.kind = MediumKind::non_overlapping;
  pair_options.porosity = 0.79;
  pair_options.r_min = r_min, pair_options.r_max = r_max;
  const Medium m079 = generate_medium(pair_options);
  const Medium m200_image = image_medium(pore_image(m200, static_cast<int>(4 * m200.width)));
  const std::vector<std::pair<std::string, std::function<Work()>>> scenes{
      {"free-fall", free_fall},
      {"medium-200", [&] { return stepping(m200, 300'000); }},
      {"medium-5000", [&] { return stepping(m5000, 300'000); }},
      {"medium-200-red-black", [&] { return stepping(m200, 300'000, ConstraintOrder::red_black); }},
      {"medium-200-image", [&] { return stepping(m200_image, 300'000); }},
      {"batch-1lane-1thread", [&] { return batch(m200, 1, 1); }},
      {"batch-1thread", [&] { return batch(m200, 1, BatchOptions{}.lanes); }},
      {"batch-1thread-image", [&] { return batch(m200_image, 1, BatchOptions{}.lanes); }},
      {"batch", [&] { return batch(m200, threads, BatchOptions{}.lanes); }},
      {"sweep-1thread", [] { return sweep(1, 16); }},
      {"sweep", [&] { return sweep(threads, 16); }},
      {"sweep-long-1thread", [] { return sweep(1, 64); }},
      {"sweep-long", [&] { return sweep(threads, 64); }},
      {"search-l1-1thread", [] { return search(1, 1); }},
      {"search-l1", [&] { return search(1, threads); }},
      {"search-l2-1thread", [] { return search(2, 1); }},
      {"search-l2", [&] { return search(2, threads); }},
      {"search-l2-long-1thread", [] { return search(2, 1, 400); }},
      {"search-l2-long", [&] { return search(2, threads, 400); }},
      {"search-l1-red-black-1thread", [] { return search(1, 1, 0, ConstraintOrder::red_black); }},
      {"search-l1-red-black", [&] { return search(1, threads, 0, ConstraintOrder::red_black); }},
      {"search-l2-red-black-1thread", [] { return search(2, 1, 0, ConstraintOrder::red_black); }},
      {"search-l2-red-black", [&] { return search(2, threads, 0, ConstraintOrder::red_black); }},
      {"search-l2-long-red-black-1thread", [] { return search(2, 1, 400, ConstraintOrder::red_black); }},
      {"search-l2-long-red-black", [&] { return search(2, threads, 400, ConstraintOrder::red_black); }},
      {"search-es-l8-1thread", [] { return search(8, 1, 0, ConstraintOrder::sequential, true); }},
      {"search-es-l8", [&] { return search(8, threads, 0, ConstraintOrder::sequential, true); }},
      {"search-es-l8-long-1thread", [] { return search(8, 1, 200, ConstraintOrder::sequential, true); }},
      {"search-es-l8-long", [&] { return search(8, threads, 200, ConstraintOrder::sequential, true); }},
      {"search-mean-1thread", [] { return search(8, 1, 15, ConstraintOrder::sequential, true, 16); }},
      {"search-mean", [&] { return search(8, threads, 15, ConstraintOrder::sequential, true, 16); }},
      {"one-droplet-079-1thread", [&] { return two_droplets(m079, 24, true); }},
      {"two-droplets-079-1thread", [&] { return two_droplets(m079, 24, false); }},
      {"one-droplet-079-batch-1thread", [&] { return two_droplet_batch(m079, 48, true); }},
      {"two-droplets-079-batch-1thread", [&] { return two_droplet_batch(m079, 48, false); }},
  };
  std::ostringstream csv;
  csv << "# machine: " << machine() << "\n# compiler: GCC " << __VERSION__ << ", "
#ifdef NDEBUG
      << "release"
#else
      << "debug"
#endif
      << " build\n# constraint vector width: " << static_cast<int>(constraint_vector_width())
      << " doubles (8: AVX-512, 4: AVX, 2: SSE2)\n# droplet: " << droplet_name
      << "\nscene,threads,repeats,grains,seconds_min,seconds_median,steps_per_s,mass_updates_per_s,"
         "droplets_per_s,evaluations_per_s,peak_rss_mb,dropped_steps_per_kept\n";
  bool any = false;
  for (const auto& [name, run] : scenes) {
    if (scene != "all" && ("," + scene + ",").find("," + name + ",") == std::string::npos) continue;
    any = true;
    std::vector<Work> ws;
    for (int r = 0; r < repeats; ++r) ws.push_back(run());
    std::sort(ws.begin(), ws.end(), [](const Work& a, const Work& b) { return a.seconds < b.seconds; });
    const Work& best = ws.front();
    const double median = ws[ws.size() / 2].seconds;
    const int used =
        name.find("1thread") != std::string::npos || name.rfind("medium", 0) == 0 || name == "free-fall" ? 1 : threads;
    csv << name << ',' << used << ',' << repeats << ',' << best.grains << ',' << best.seconds << ',' << median << ','
        << best.steps / best.seconds << ',' << best.mass_updates / best.seconds << ',' << best.droplets / best.seconds
        << ',' << best.evaluations / best.seconds << ',' << peak_rss_mb() << ','
        << (best.steps > 0 ? best.dropped_steps / best.steps : 0.0) << '\n';
    std::cerr << name << ": " << best.steps / best.seconds << " steps/s, " << best.mass_updates / best.seconds
              << " mass updates/s (min " << best.seconds << " s, median " << median << " s)\n";
  }
  if (!any) {
    std::cerr << "bench_scenes: unknown scene " << scene << "\n";
    return 2;
  }
  if (out.empty())
    std::cout << csv.str();
  else
    std::ofstream(out) << csv.str();
  return 0;
}
