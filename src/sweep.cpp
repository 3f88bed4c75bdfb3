#include "softdrop/sweep.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "softdrop/batch.hpp"
#include "softdrop/porosity.hpp"
#include "softdrop/random.hpp"
#include "validation.hpp"

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

std::uint64_t sweep_medium_seed(const SweepOptions& o, const SweepUnit& u) {
  const auto micro = static_cast<std::uint64_t>(std::llround(o.porosities.at(static_cast<std::size_t>(u.porosity)) * 1e9));
  return derive_seed(derive_seed(o.seed, micro), static_cast<std::uint64_t>(u.medium));
}

SweepMedium run_sweep_unit(const SweepOptions& o, const SweepUnit& u, int threads,
                           const std::function<void(int, int)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  SweepMedium r;
  r.unit = u;
  r.target_porosity = o.porosities.at(static_cast<std::size_t>(u.porosity));
  r.medium_seed = sweep_medium_seed(o, u);
  MediumOptions mo = o.medium;
  mo.porosity = r.target_porosity;
  mo.seed = r.medium_seed;
  const Medium medium = generate_medium(mo);
  r.porosity = exact_porosity(medium);
  r.grains = static_cast<int>(medium.grains.size());
  BatchOptions b;
  b.droplets = o.droplets;
  b.seed = derive_seed(r.medium_seed, 0x5354415254ULL);  // "START"
  b.threads = threads;
  RunOptions run = o.run;
  run.path_interval = 0;
  run.area_interval = 0;
  run.snapshot_times.clear();
  const std::vector<RunSummary> runs = run_batch(o.droplet, medium, run, b, progress);
  const BatchStats s = summarize(runs);
  r.passed = s.passed;
  r.stuck = s.stuck;
  r.timeout = s.timeout;
  r.diverged = s.diverged;
  r.mean_t = s.mean_tortuosity;
  r.standard_error = s.standard_error;
  r.stuck_fraction = s.stuck_fraction;
  for (std::size_t i = 0; i < runs.size(); ++i)
    r.droplets.push_back({static_cast<int>(i), runs[i].start_x, runs[i].outcome,
                          runs[i].outcome == Outcome::passed ? runs[i].tortuosity : 0.0, runs[i].steps});
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::vector<SweepPoint> sweep_points(const std::vector<SweepMedium>& media) {
  std::map<double, std::vector<const SweepMedium*>> by;
  for (const SweepMedium& m : media) by[m.target_porosity].push_back(&m);
  std::vector<SweepPoint> out;
  for (const auto& [target, list] : by) {
    SweepPoint p;
    p.target_porosity = target;
    double phi = 0, sum = 0;
    for (const SweepMedium* m : list) {
      ++p.media;
      phi += m->porosity;
      for (const SweepDroplet& d : m->droplets) {
        ++p.droplets;
        if (d.outcome == Outcome::stuck) ++p.stuck;
        if (d.outcome == Outcome::passed) ++p.passed, sum += d.tortuosity;
      }
    }
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
