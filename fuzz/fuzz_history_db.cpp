// Fuzz target: SQLite databases (search histories and sweep stores), mutated two ways:
// - an input that starts with the SQLite header is the database file itself (byte-level damage);
// - any other input is SQL run on a copy of a valid seed database from the corpus (odd first
//   byte: the search history, even: the sweep store), so values, rows and schema can be wrong in
//   ways that still pass SQLite's own checks (NaN where a number belongs, missing rows, huge counts).
// The file is then opened and read the way `history`, `export`, `optimize --resume` and
// `sweep-report` do, then opened for writing (which migrates old schemas and marks a status). It
// must be refused or read with std::runtime_error (SQLite's errors are runtime_errors too), never a
// crash, a sanitizer report, a hang or a large allocation.
#include <sqlite3.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "softdrop/store.hpp"
#include "softdrop/sweep.hpp"
#include "studies/averaging.hpp"
#include "studies/fit.hpp"

namespace {

void read_history(const std::string& path, softdrop::OpenMode mode) {
  auto history = softdrop::open_history(path, mode);
  for (const softdrop::RunRecord& r : history->runs()) {
    (void)history->run(r.id);
    (void)history->generations(r.id);
    (void)history->configuration(r.id, -1);
    (void)history->configuration(r.id, 0);
    if (mode == softdrop::OpenMode::create) history->set_status(r.id, "interrupted");
  }
}

// What sweep-report, fit and averagings do with a store's media.
void read_sweeps(const std::string& path) {
  auto store = softdrop::open_sweep_store(path, softdrop::OpenMode::read_only);
  for (const softdrop::SweepRecord& s : store->sweeps()) {
    (void)store->done_units(s.id);
    const std::vector<softdrop::SweepMedium> media = store->media(s.id);
    std::vector<softdrop::FitPoint> points;
    for (const softdrop::SweepPoint& p : softdrop::sweep_points(media))
      if (p.passed > 1 && p.standard_error > 0) points.push_back({p.porosity, p.mean_t, p.standard_error});
    for (const auto law : {softdrop::FitLaw::power, softdrop::FitLaw::log}) {
      try {
        (void)softdrop::fit_law(law, points);
      } catch (const std::invalid_argument&) {
      }
    }
    std::vector<softdrop::MediumPoint> by_medium;
    for (const softdrop::SweepMedium& m : media)
      if (m.passed > 0) by_medium.push_back({m.porosity, m.mean_t});
    (void)softdrop::group_averages(by_medium, softdrop::AveragingType::by_t, 2);
  }
}

std::string slurp(const char* path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The SQL may change rows and the schema of the copy, but not reach other files or settings.
int authorize(void*, int action, const char*, const char*, const char*, const char*) {
  switch (action) {
    case SQLITE_ATTACH:
    case SQLITE_DETACH:
    case SQLITE_PRAGMA:
    case SQLITE_TRANSACTION:
      return SQLITE_DENY;
    default:
      return SQLITE_OK;
  }
}

void write_file(const std::string& path, const char* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data, static_cast<std::streamsize>(size));
}

/// The fuzzer's scratch database, removed with SQLite's companions when the fuzzer exits normally.
struct ScratchDb {
  std::string path = "/tmp/softdrop-fuzz-db-" + std::to_string(::getpid()) + ".db";
  void clear() const {
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::remove((path + suffix).c_str());
  }
  ~ScratchDb() { clear(); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ScratchDb scratch;
  const std::string& path = scratch.path;
  static const std::string history_seed = slurp(SOFTDROP_FUZZ_CORPUS "/history_db/history.db");
  static const std::string sweep_seed = slurp(SOFTDROP_FUZZ_CORPUS "/history_db/sweep.db");
  scratch.clear();
  const char* bytes = reinterpret_cast<const char*>(data);
  if (size >= 6 && std::memcmp(bytes, "SQLite", 6) == 0) {
    write_file(path, bytes, size);
  } else {
    if (size == 0) return 0;
    const std::string& seed = (data[0] & 1) ? history_seed : sweep_seed;
    write_file(path, seed.data(), seed.size());
    const std::string sql(bytes + 1, size - 1);
    sqlite3* db = nullptr;
    if (sqlite3_open(path.c_str(), &db) == SQLITE_OK) {
      sqlite3_set_authorizer(db, authorize, nullptr);
      sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);  // runs statements up to the first error
    }
    sqlite3_close(db);
  }
  try {
    read_history(path, softdrop::OpenMode::read_only);
  } catch (const std::runtime_error&) {
  }
  try {
    read_sweeps(path);
  } catch (const std::runtime_error&) {
  }
  try {
    read_history(path, softdrop::OpenMode::create);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
