#include "softdrop/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "sim/interleaved.hpp"
#include "sim/lane_policy.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"
#include "studies/media_error.hpp"
#include "util/enum_names.hpp"
#include "util/random.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {
using detail::fail;
using detail::num;

bool SweepOptions::IsValid(std::string* why) const {
  if (porosities.empty()) return fail(why, "porosities: at least one is needed");
  for (std::size_t i = 0; i < porosities.size(); ++i) {
    const double p = porosities[i];
    if (!std::isfinite(p) || p <= 0 || p >= 1) return fail(why, "porosities = " + num(p) + ": each must be in (0, 1)");
    for (std::size_t j = 0; j < i; ++j)
      if (porosities[j] == p) return fail(why, "porosities = " + num(p) + ": listed twice");
  }
  if (media < 1 || media > 1'000'000) return fail(why, "media = " + std::to_string(media) + ": must be in [1, 1e6]");
  if (droplets < 1 || droplets > 1'000'000)
    return fail(why, "droplets = " + std::to_string(droplets) + ": must be in [1, 1e6]");
  MediumOptions m = medium;
  m.porosity = porosities.front();
  if (!m.IsValid(why)) return false;
  if (!droplet.IsValid(why)) return false;
  if (second && !second->IsValid(droplet, why)) return false;
  if (second && !medium.periodic && second->offset_x != 0)
    return fail(why,
                "second-offset-x: a sweep between walls takes none (a random start could put the second droplet "
                "outside them)");
  return run.IsValid(why);
}

std::vector<SweepUnit> sweep_units(const SweepOptions& o, int shard, int shards) {
  if (shards < 1 || shard < 0 || shard >= shards)
    throw std::invalid_argument("shard = " + std::to_string(shard) + "/" + std::to_string(shards) +
                                ": must be i/n with 0 <= i < n");
  std::vector<SweepUnit> units;
  long index = 0;
  for (int p = 0; p < static_cast<int>(o.porosities.size()); ++p)
    for (int m = 0; m < o.media; ++m, ++index)
      if (index % shards == shard) units.push_back({p, m});
  return units;
}

constexpr detail::EnumName<MediaStream> kMediaStreams[] = {{MediaStream::held_out, "held-out"},
                                                           {MediaStream::calibration, "calibration"}};

const char* to_string(MediaStream stream) { return detail::name_of(kMediaStreams, stream); }

MediaStream parse_media_stream(const std::string& name) {
  return detail::parse_name(kMediaStreams, name, "media-stream");
}

std::vector<std::string> media_stream_names() { return detail::name_list(kMediaStreams); }

std::uint64_t sweep_medium_seed(const SweepOptions& o, const SweepUnit& u) {
  const auto micro =
      static_cast<std::uint64_t>(std::llround(o.porosities.at(static_cast<std::size_t>(u.porosity)) * 1e9));
  // The calibration stream is the derivation every store before the streams used; the held-out
  // stream starts from the seed hashed with its own tag, so no seed of one is a seed of the other.
  const std::uint64_t base =
      o.stream == MediaStream::calibration ? o.seed : derive_seed(o.seed, 0x48454C444F5554ULL);  // "HELDOUT"
  return derive_seed(derive_seed(base, micro), static_cast<std::uint64_t>(u.medium));
}

MediumOptions sweep_medium_options(const SweepOptions& o, const SweepUnit& u) {
  MediumOptions mo = o.medium;
  mo.porosity = o.porosities.at(static_cast<std::size_t>(u.porosity));
  mo.seed = sweep_medium_seed(o, u);
  return mo;
}

namespace {

// A unit's medium and the options of its droplets: the one definition both runners use.
struct UnitSetup {
  SweepMedium record;  // identity, seeds and medium figures; droplets and counts come later
  Medium medium;
  BatchOptions batch;
  RunOptions run;
  // A droplet in `medium`, made once the setup has its place: the unit's droplets are its
  // copies, which share its model (the grain grid, the step's constants) instead of each
  // building its own.
  std::optional<Simulation> prototype;
};

UnitSetup setup_unit(const SweepOptions& o, const SweepUnit& u) {
  UnitSetup s;
  s.record.unit = u;
  const MediumOptions mo = sweep_medium_options(o, u);
  s.record.target_porosity = mo.porosity;
  s.record.medium_seed = mo.seed;
  s.medium = generate_medium(mo);
  s.record.porosity = exact_porosity(s.medium);
  s.record.grains = static_cast<int>(s.medium.grains.size());
  s.batch.droplets = o.droplets;
  s.batch.seed = derive_seed(s.record.medium_seed, 0x5354415254ULL);  // "START"
  s.run = o.run;
  s.run.path_interval = 0;
  s.run.area_interval = 0;
  s.run.snapshot_times.clear();
  return s;
}

void finish_unit(SweepMedium* r, const std::vector<RunSummary>& runs) {
  const BatchStats s = summarize(runs);
  r->passed = s.passed;
  r->stuck = s.stuck;
  r->timeout = s.timeout;
  r->diverged = s.diverged;
  r->mean_t = s.mean_tortuosity;
  r->standard_error = s.standard_error;
  r->stuck_fraction = s.stuck_fraction;
  r->droplets.clear();
  for (std::size_t i = 0; i < runs.size(); ++i)
    r->droplets.push_back(
        {static_cast<int>(i), runs[i].start_x, runs[i].outcome,
         runs[i].outcome == Outcome::passed ? runs[i].tortuosity : 0.0, runs[i].steps, runs[i].shaken_at,
         runs[i].outcome == Outcome::passed ? runs[i].route_tortuosity : std::numeric_limits<double>::quiet_NaN()});
}

// A pair sweep's unit: the firsts are the droplets (their counts and <T> the medium's), and each
// released second is recorded with its pair's contacts.
void finish_pair_unit(SweepMedium* r, const std::vector<TwoDropletSummary>& pairs) {
  std::vector<RunSummary> firsts;
  firsts.reserve(pairs.size());
  for (const TwoDropletSummary& p : pairs) firsts.push_back(p.first);
  finish_unit(r, firsts);
  r->second_droplets.clear();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const TwoDropletSummary& p = pairs[i];
    if (!p.released) continue;
    const RunSummary& s = p.second;
    const bool passed = s.outcome == Outcome::passed;
    r->second_droplets.push_back({{static_cast<int>(i), s.start_x, s.outcome, passed ? s.tortuosity : 0.0, s.steps,
                                   s.shaken_at, passed ? s.route_tortuosity : std::numeric_limits<double>::quiet_NaN()},
                                  p.released_at,
                                  p.first_held_at,
                                  p.second_held_at,
                                  p.contact_steps,
                                  p.shared_touched});
  }
}

// A unit run whole with `threads` threads: the droplets (or pairs) from its starts.
SweepMedium run_unit(const SweepOptions& o, const SweepUnit& u, int threads,
                     const std::function<void(int, int)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  UnitSetup s = setup_unit(o, u);
  s.batch.threads = threads;
  if (o.second)
    finish_pair_unit(&s.record, run_two_droplet_batch(o.droplet, s.medium, s.run, s.batch, *o.second, progress));
  else
    finish_unit(&s.record, run_batch(o.droplet, s.medium, s.run, s.batch, progress));
  s.record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return std::move(s.record);
}

}  // namespace

SweepMedium run_sweep_unit(const SweepOptions& o, const SweepUnit& u, int threads,
                           const std::function<void(int, int)>& progress) {
  return run_unit(o, u, threads, progress);
}

void run_sweep_units(const SweepOptions& o, const std::vector<SweepUnit>& units, int threads,
                     const std::function<void(SweepMedium&&)>& on_done, const std::function<bool()>& stop,
                     const std::function<bool(const SweepUnit&)>& skip) {
  if (o.second) {  // pairs: a unit at a time, its pairs across the threads
    for (const SweepUnit& u : units) {
      if (stop && stop()) return;
      if (skip && skip(u)) continue;
      on_done(run_unit(o, u, threads, {}));
    }
    return;
  }
  const int workers = detail::worker_threads(threads);
  struct Open {
    std::once_flag made;
    std::unique_ptr<UnitSetup> setup;
    std::exception_ptr error;
    std::vector<RunSummary> runs;
    // Droplet d's simulation while it runs. Any worker may finish a droplet (the lane exchange
    // hands the last ones to idle workers), so they are kept by droplet, not by worker.
    std::vector<std::unique_ptr<Simulation>> sims;
    int remaining = 0;
    std::chrono::steady_clock::time_point t0;
  };
  std::vector<Open> open(units.size());
  std::mutex m;
  std::condition_variable cv;
  std::size_t next_unit = 0, completed_units = 0;
  int next_droplet = 0;
  bool stopping = false;
  std::exception_ptr error;
  std::vector<std::size_t> ready;  // completed units waiting for on_done
  // Each worker steps up to `lanes` droplets together (run_interleaved); a droplet's summary does
  // not depend on which worker or lane ran it, nor on its lane mates.
  const int lanes = interleaved_lanes();
  // Units from the oldest not yet committed that may be open: one per worker and one more, plus
  // enough that their droplets fill every lane twice over, so that a unit still waiting for its
  // slowest (stuck) droplets does not leave lanes idle when media have few droplets each.
  const std::size_t window = static_cast<std::size_t>(workers) + 1 +
                             static_cast<std::size_t>((2 * workers * lanes + o.droplets - 1) / std::max(1, o.droplets));
  std::size_t oldest_open = 0;  // units before it are complete
  int active = 0;               // droplets being simulated
  LaneExchange exchange;

  const std::int64_t per_unit = o.droplets;
  auto worker = [&] {
    auto next = [&](DropletJob* job, bool may_wait) {
      std::unique_lock lock(m);
      auto can_take = [&] { return stopping || next_unit == units.size() || next_unit < oldest_open + window; };
      if (may_wait) cv.wait(lock, can_take);
      if (!can_take() || stopping || next_unit == units.size()) return false;
      // A stop request is honoured between units: the open units' droplets are all handed out by
      // then, so they complete and are committed; no new unit starts.
      if (next_droplet == 0 && stop && stop()) {
        stopping = true;
        cv.notify_all();
        return false;
      }
      // Units stored by another process are passed over as if committed here.
      while (next_droplet == 0 && next_unit < units.size() && skip && skip(units[next_unit])) {
        open[next_unit].remaining = -1;
        ++completed_units;
        ++next_unit;
        while (oldest_open < units.size() && open[oldest_open].remaining == -1) ++oldest_open;
        cv.notify_all();
      }
      if (next_unit == units.size()) return false;
      const std::size_t u = next_unit;
      const int d = next_droplet;
      if (d == 0) {
        open[u].runs.resize(static_cast<std::size_t>(o.droplets));
        open[u].sims.resize(static_cast<std::size_t>(o.droplets));
        open[u].remaining = o.droplets;
        open[u].t0 = std::chrono::steady_clock::now();
      }
      if (++next_droplet == o.droplets) next_droplet = 0, ++next_unit;
      ++active;
      lock.unlock();
      try {
        std::call_once(open[u].made, [&] {
          open[u].setup = std::make_unique<UnitSetup>(setup_unit(o, units[u]));
          open[u].setup->prototype.emplace(o.droplet, open[u].setup->medium);
        });
        const UnitSetup& s = *open[u].setup;
        std::unique_ptr<Simulation>& sim = open[u].sims[static_cast<std::size_t>(d)];
        sim = std::make_unique<Simulation>(*s.prototype);
        job->sim = sim.get();
        job->x0 = batch_start_x(s.batch, s.medium, o.droplet, d);
        job->options = &s.run;
        job->id = static_cast<std::int64_t>(u) * per_unit + d;
      } catch (...) {
        lock.lock();
        --active;
        throw;
      }
      return true;
    };
    auto done = [&](std::int64_t id, RunSummary&& summary) {
      const auto u = static_cast<std::size_t>(id / per_unit);
      open[u].runs[static_cast<std::size_t>(id % per_unit)] = std::move(summary);
      open[u].sims[static_cast<std::size_t>(id % per_unit)].reset();
      std::lock_guard lock(m);
      --active;
      cv.notify_all();
      if (--open[u].remaining == 0) ready.push_back(u);
    };
    try {
      run_interleaved(lanes, next, done, nullptr, &exchange);
    } catch (...) {
      // The droplets this worker was stepping will not finish; with the error set, the loop below
      // no longer waits for them.
      std::lock_guard lock(m);
      if (!error) error = std::current_exception();
      stopping = true;
      cv.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < workers; ++i) pool.emplace_back(worker);
  {
    std::unique_lock lock(m);
    for (;;) {
      // Done when every unit is committed, on an error, or when stopping with no droplet in flight
      // (then nothing more can complete).
      cv.wait(lock,
              [&] { return !ready.empty() || error || completed_units == units.size() || (stopping && active == 0); });
      if (error || completed_units == units.size()) break;
      if (ready.empty()) break;
      const std::size_t u = ready.back();
      ready.pop_back();
      lock.unlock();
      SweepMedium record = std::move(open[u].setup->record);
      finish_unit(&record, open[u].runs);
      record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - open[u].t0).count();
      open[u].setup.reset();
      open[u].runs = {};
      open[u].sims.clear();
      open[u].sims.shrink_to_fit();
      try {
        on_done(std::move(record));
      } catch (...) {
        lock.lock();
        error = std::current_exception();
        stopping = true;
        cv.notify_all();
        break;
      }
      lock.lock();
      ++completed_units;
      open[u].remaining = -1;  // committed
      while (oldest_open < units.size() && open[oldest_open].remaining == -1) ++oldest_open;
      cv.notify_all();
    }
    stopping = true;
  }
  cv.notify_all();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

std::vector<SweepPoint> sweep_points(const std::vector<SweepMedium>& media, bool second_droplets) {
  if (second_droplets) {  // the seconds as the droplets of copies of the media
    std::vector<SweepMedium> as_droplets;
    for (const SweepMedium& m : media) {
      SweepMedium c;
      c.target_porosity = m.target_porosity, c.porosity = m.porosity;
      for (const SweepSecond& s : m.second_droplets) c.droplets.push_back(s.run);
      as_droplets.push_back(std::move(c));
    }
    return sweep_points(as_droplets);
  }
  std::map<double, std::vector<const SweepMedium*>> by;
  for (const SweepMedium& m : media) by[m.target_porosity].push_back(&m);
  std::vector<SweepPoint> out;
  for (const auto& [target, list] : by) {
    SweepPoint p;
    p.target_porosity = target;
    double phi = 0, sum = 0;
    detail::MediaMean by_medium;
    for (const SweepMedium* m : list) {
      ++p.media;
      phi += m->porosity;
      int passed = 0;
      double medium_sum = 0;
      for (const SweepDroplet& d : m->droplets) {
        ++p.droplets;
        if (d.outcome == Outcome::stuck) ++p.stuck;
        if (d.outcome == Outcome::diverged) ++p.diverged;
        if (d.outcome == Outcome::passed) ++p.passed, ++passed, sum += d.tortuosity, medium_sum += d.tortuosity;
      }
      by_medium.add_medium(passed, medium_sum);
    }
    p.media_passed = by_medium.media();
    p.media_standard_error = by_medium.standard_error();
    p.per_medium_t = by_medium.per_medium_mean();
    p.per_medium_standard_error = by_medium.per_medium_standard_error();
    p.porosity = phi / p.media;
    p.stuck_fraction = p.droplets ? static_cast<double>(p.stuck) / p.droplets : 0.0;
    if (p.passed > 0) p.mean_t = sum / p.passed;
    if (p.passed > 1) {
      double ss = 0;
      for (const SweepMedium* m : list)
        for (const SweepDroplet& d : m->droplets)
          if (d.outcome == Outcome::passed) ss += (d.tortuosity - p.mean_t) * (d.tortuosity - p.mean_t);
      p.standard_error = std::sqrt(ss / (p.passed - 1) / p.passed);
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace softdrop
