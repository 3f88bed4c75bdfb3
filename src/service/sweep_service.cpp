// A sweep's run on a database (softdrop/service.hpp): resume from the stored media, store each
// medium as it ends, stop on request, and say how it ended.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "softdrop/service.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {

bool SweepRun::IsValid(std::string* why) const {
  using detail::fail;
  if (!sweep.IsValid(why)) return false;
  if (db.empty()) return fail(why, "db: an empty file name");
  if (!detail::valid_threads(threads, why)) return false;
  if (shards < 1 || shard < 0 || shard >= shards)
    return fail(why,
                "shard = " + std::to_string(shard) + "/" + std::to_string(shards) + ": expected i/n with 0 <= i < n");
  return true;
}

SweepSummary run_sweep(const SweepRun& run, SweepObserver& observer, const SweepUnitsRunner& runner) {
  std::string why;
  if (!run.IsValid(&why)) throw std::invalid_argument(why);
  const std::string params = sweep_params_to_json(run.sweep);
  std::unique_ptr<SweepStore> store;
  std::int64_t id = 0;
  std::vector<SweepUnit> stored_before;
  if (std::filesystem::exists(run.db)) {
    store = open_sweep_store(run.db, OpenMode::create);
    id = store->find(params);
    if (id > 0)  // every stored row read now: a damaged one refuses the sweep here
      for (const SweepMedium& m : store->media(id)) stored_before.push_back(m.unit);
  } else {
    check_database(run.db);  // a new file: its folder must exist and be writable
  }
  const auto sweep_id = [&] {  // the store and the sweep's record, made when first needed
    if (!store) store = open_sweep_store(run.db, OpenMode::create);
    if (id == 0) id = store->find_or_create(params, run.sweep);
    return id;
  };
  const std::vector<SweepUnit> shard = sweep_units(run.sweep, run.shard, run.shards);
  std::vector<SweepUnit> todo;
  for (const SweepUnit& u : shard)
    if (std::find(stored_before.begin(), stored_before.end(), u) == stored_before.end()) todo.push_back(u);
  observer.started(id, shard.size() - todo.size(), todo.size());

  SweepSummary summary;
  const auto t0 = std::chrono::steady_clock::now();
  std::atomic<bool> stopped{false};
  std::size_t done = 0;
  std::mutex store_lock;  // on_done runs on this thread, `stored` on the workers
  const std::function<void(SweepMedium &&)> commit = [&](SweepMedium&& m) {
    std::lock_guard lock(store_lock);
    const auto c0 = std::chrono::steady_clock::now();
    const std::int64_t sweep = sweep_id();  // before store-> is read: it may make the store
    if (store->add(sweep, m))
      ++summary.media_this_session;
    else
      ++summary.media_by_another_process;  // stored meanwhile by another process
    const auto now = std::chrono::steady_clock::now();
    summary.commit_seconds += std::chrono::duration<double>(now - c0).count();
    ++done;
    summary.droplets_this_session += static_cast<std::int64_t>(m.droplets.size());
    const SweepProgress progress{sweep, done, todo.size(), summary.droplets_this_session,
                                 std::chrono::duration<double>(now - t0).count()};
    if (!observer.stored(m, progress)) stopped = true;
  };
  const std::function<bool()> stop = [&] {
    if (!stopped && observer.stop_requested()) stopped = true;
    return stopped.load();
  };
  const std::function<bool(const SweepUnit&)> stored_elsewhere = [&](const SweepUnit& u) {
    std::lock_guard lock(store_lock);
    if (id == 0 && store) id = store->find(params);  // another process may have begun the sweep
    if (id == 0 || !store->has_unit(id, u)) return false;
    ++done, ++summary.media_by_another_process;
    return true;
  };
  if (runner) {
    SweepUnitsRun ranks = runner(run.sweep, todo, run.threads, commit, stop, stored_elsewhere);
    summary.by_rank = std::move(ranks.by_rank);
    summary.serve_seconds = ranks.serve_seconds;
  } else {
    run_sweep_units(run.sweep, todo, run.threads, commit, stop, stored_elsewhere);
  }
  summary.sweep = sweep_id();  // a sweep stopped before its first medium is recorded as begun
  const SweepRecord record = store->sweep(summary.sweep);
  summary.status = record.done == record.units ? "complete" : stopped ? "interrupted" : "running";
  store->set_status(summary.sweep, summary.status);
  summary.media = record.units;
  summary.done = record.done;
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace softdrop
