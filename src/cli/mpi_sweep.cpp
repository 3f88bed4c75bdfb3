#include "cli/mpi_sweep.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "studies/sweep_record_bytes.hpp"

namespace softdrop::cli {
namespace {

// Message tags.
constexpr int kClaim = 1;       // rank -> 0: may I run unit i? (i: index into the todo list)
constexpr int kClaimReply = 2;  // 0 -> rank: i itself (yes), or the first unit not yet handed out
constexpr int kRecord = 3;      // rank -> 0: a finished unit's record
constexpr int kDone = 4;        // rank -> 0: no more units here

std::string int_bytes(long v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); }
long bytes_int(const std::string& b) {
  if (b.size() != sizeof(long)) throw std::runtime_error("MPI: a malformed message");
  long v = 0;
  std::memcpy(&v, b.data(), sizeof v);
  return v;
}

// Every rank goes through the list in order and asks for each unit it has not been told is
// taken, so the units handed out are always a prefix of the list: rank 0 keeps its length.
class Ledger {
 public:
  Ledger(const std::vector<SweepUnit>& todo, const std::function<bool()>& stop,
         const std::function<bool(const SweepUnit&)>& stored)
      : todo_(todo), stop_(stop), stored_(stored) {}
  /// `unit` if it is handed to the asker, else the first unit not handed out (todo.size(): none).
  std::size_t claim(std::size_t unit) {
    std::lock_guard lock(m_);
    if (stop_ && stop_()) next_ = todo_.size();
    while (next_ < todo_.size() && stored_ && stored_(todo_[next_])) ++next_;
    if (unit == next_ && next_ < todo_.size()) return next_++;
    return next_ > unit ? next_ : unit + 1;  // (asked ahead of the prefix: cannot happen)
  }

 private:
  const std::vector<SweepUnit>& todo_;
  const std::function<bool()>& stop_;
  const std::function<bool(const SweepUnit&)>& stored_;
  std::mutex m_;
  std::size_t next_ = 0;
};

std::vector<int> flatten(const std::vector<SweepUnit>& units) {
  std::vector<int> v;
  for (const SweepUnit& u : units) v.push_back(u.porosity), v.push_back(u.medium);
  return v;
}

// Unit -> its index in the list.
std::map<std::pair<int, int>, std::size_t> index_of(const std::vector<SweepUnit>& units) {
  std::map<std::pair<int, int>, std::size_t> index;
  for (std::size_t i = 0; i < units.size(); ++i) index[{units[i].porosity, units[i].medium}] = i;
  return index;
}

}  // namespace

RanksReport run_sweep_units_on_ranks(const Job& job, const SweepOptions& options, const std::vector<SweepUnit>& todo,
                                     int threads, const std::function<void(SweepMedium&&)>& on_done,
                                     const std::function<bool()>& stop,
                                     const std::function<bool(const SweepUnit&)>& stored) {
  std::vector<int> list = flatten(todo);
  mpi::broadcast(list);
  Ledger ledger(todo, stop, stored);
  std::mutex committing;  // on_done one record at a time, from this rank's units or another's
  std::vector<int> ran(static_cast<std::size_t>(job.size()), 0);
  double serving = 0;
  // The other ranks' messages, served on a thread of their own while this rank runs units.
  std::thread server([&] {
    try {
      for (int done = 0; done < job.size() - 1;) {
        int sender = 0, tag = 0;
        const std::string message = mpi::receive(-1, -1, &sender, &tag);
        const auto t0 = std::chrono::steady_clock::now();
        if (tag == kClaim) {
          mpi::send(sender, kClaimReply,
                    int_bytes(static_cast<long>(ledger.claim(static_cast<std::size_t>(bytes_int(message))))));
        } else if (tag == kRecord) {
          SweepMedium record = decode_sweep_medium(message);
          std::lock_guard lock(committing);
          ++ran[static_cast<std::size_t>(sender)];
          on_done(std::move(record));
        } else if (tag == kDone) {
          ++done;
        }
        serving += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
    } catch (const std::exception& e) {
      job.fail(e);
    }
  });
  const auto index = index_of(todo);
  try {
    run_sweep_units(
        options, todo, threads,
        [&](SweepMedium&& m) {
          std::lock_guard lock(committing);
          ++ran[0];
          on_done(std::move(m));
        },
        stop,
        [&](const SweepUnit& u) {
          return ledger.claim(index.at({u.porosity, u.medium})) != index.at({u.porosity, u.medium});
        });
  } catch (const std::exception& e) {
    job.fail(e);
  }
  server.join();
  return {ran, serving};
}

void work_on_sweep_units(const Job& job, const SweepOptions& options, int threads) {
  try {
    std::vector<int> list;
    mpi::broadcast(list);
    std::vector<SweepUnit> todo;
    for (std::size_t i = 0; i + 1 < list.size(); i += 2) todo.push_back({list[i], list[i + 1]});
    const auto index = index_of(todo);
    std::size_t first_free = 0;  // units before it are handed out (skip is called under the scheduler's lock)
    run_sweep_units(
        options, todo, threads, [&](SweepMedium&& m) { mpi::send(0, kRecord, encode_sweep_medium(m)); }, {},
        [&](const SweepUnit& u) {
          const std::size_t i = index.at({u.porosity, u.medium});
          if (i < first_free) return true;
          mpi::send(0, kClaim, int_bytes(static_cast<long>(i)));
          const auto answer = static_cast<std::size_t>(bytes_int(mpi::receive(0, kClaimReply)));
          if (answer == i) return false;
          first_free = answer;
          return true;
        });
    mpi::send(0, kDone, "");
  } catch (const std::exception& e) {
    job.fail(e);
  }
}

}  // namespace softdrop::cli
