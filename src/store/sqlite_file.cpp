#include "sqlite_file.hpp"

#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "sqlite_schema.hpp"
#include "wal_file.hpp"

namespace softdrop::detail {

bool has_column(SQLite::Database& db, const char* table, const char* column) {
  return db.execAndGet(std::string("SELECT count(*) FROM pragma_table_info('") + table + "') WHERE name = '" + column +
                       "'")
             .getInt() > 0;
}

namespace {

// Version 4 lets a generation's kind be 'relocate', version 5 'migrate', version 8 'mixed'. Earlier files have a
// narrower CHECK, which no stored row can break when widened: it is rewritten in place by SQLite's
// documented procedure for constraint changes that leave the stored rows valid (the table's SQL in
// sqlite_master, and schema_version bumped so that every connection rereads it), in the caller's
// transaction.
void widen_generation_kinds(SQLite::Database& db) {
  const std::string open = "CHECK (kind IN (",
                    after = "CHECK (kind IN ('initial', 'all', 'single', 'relocate', 'migrate', 'mixed'))";
  std::string sql =
      db.execAndGet("SELECT sql FROM sqlite_master WHERE type = 'table' AND name = 'generations'").getString();
  const auto at = sql.find(open);
  const auto end = at == std::string::npos ? at : sql.find("))", at);
  if (end == std::string::npos) return;
  if (sql.compare(at, end + 2 - at, after) == 0) return;  // made at version 5, or widened already
  sql.replace(at, end + 2 - at, after);
  const int schema_version = db.execAndGet("PRAGMA schema_version").getInt();
  db.exec("PRAGMA writable_schema = ON");
  SQLite::Statement update(db, "UPDATE sqlite_master SET sql = ? WHERE type = 'table' AND name = 'generations'");
  update.bind(1, sql);
  update.exec();
  db.exec("PRAGMA schema_version = " + std::to_string(schema_version + 1));
  db.exec("PRAGMA writable_schema = OFF");
}

// Version 5 also gives each run its island (NULL: not one of islands) and the id of its
// archipelago's first run.
// Adds a column where it is not already (a file whose version was set back, or a migration a
// crash interrupted before it set the version, may have it).
void add_column(SQLite::Database& db, const AddedColumn& c) {
  if (!has_column(db, c.table, c.column))
    db.exec(std::string("ALTER TABLE ") + c.table + " ADD COLUMN " + c.column + " " + c.type);
}

void add_island_columns(SQLite::Database& db) {
  for (const char* column : {"island", "archipelago"}) add_column(db, {"runs", column, "INTEGER"});
}

// The tables of the current schema; those starting "sweep" came with version 2, validations with 6.
constexpr const char* kTables[] = {"runs",   "generations", "candidates",     "grains",     "paths",
                                   "sweeps", "sweep_media", "sweep_droplets", "validations"};

// A WAL file's header; frames follow it.
constexpr off_t kWalHeaderBytes = 32;

// The size of the file at `path` in bytes, -1 if there is none.
off_t file_size(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? st.st_size : -1;
}

// Reads what the file is before SQLite touches it: missing, empty, or an SQLite file whose header
// is consistent with its size. Returns false for "no usable content yet" (missing or empty).
bool check_file(const std::string& path, OpenMode mode) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (mode == OpenMode::read_only) throw file_error(path, "no such file");
    // A new file: its folder must be there to hold it (and its -wal and -shm).
    const std::string::size_type slash = path.rfind('/');
    const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    struct stat dir {};
    if (::stat(folder.c_str(), &dir) != 0 || !S_ISDIR(dir.st_mode))
      throw file_error(path, "folder '" + folder + "' does not exist");
    if (::access(folder.c_str(), W_OK) != 0) throw file_error(path, "folder '" + folder + "' is not writable");
    return false;
  }
  if (!S_ISREG(st.st_mode)) throw file_error(path, "not a regular file");
  if (st.st_size == 0) {
    if (mode == OpenMode::read_only) throw file_error(path, "empty file, not a softdrop database");
    return false;
  }
  if (::access(path.c_str(), R_OK) != 0)
    throw file_error(path, std::string("cannot read it (") + std::strerror(errno) + ")");
  SQLite::Header h{};
  try {
    h = SQLite::Database::getHeaderInfo(path);
  } catch (const std::exception&) {
    throw file_error(path, "not an SQLite database (no SQLite header)");
  }
  // SQLite opens a file whose write version it does not know as read-only, and refuses one whose
  // read version it does not know: both are damage here (softdrop writes 2 and 2, WAL).
  if ((h.fileFormatWriteVersion != 1 && h.fileFormatWriteVersion != 2) ||
      (h.fileFormatReadVersion != 1 && h.fileFormatReadVersion != 2))
    throw file_error(path, "damaged SQLite header (file format versions " + std::to_string(h.fileFormatWriteVersion) +
                               " and " + std::to_string(h.fileFormatReadVersion) +
                               ", bytes 18 and 19, must be 1 or 2)");
  const unsigned long page = h.pageSizeBytes == 1 ? 65536UL : h.pageSizeBytes;
  // A checkpoint copies pages from the WAL into the file, page 1 (with the new size) first, so a
  // kill, a full disk or a power cut inside it leaves a file shorter than its header says. That
  // file is valid: its missing pages are still in the WAL, and SQLite reads them from there. So
  // with WAL frames present the size is SQLite's to judge (quick_check, below, reads every page in
  // use); without them a short file really is truncated.
  const bool wal_frames = file_size(path + "-wal") > kWalHeaderBytes;
  // The in-header size is valid when the change counter matches version-valid-for.
  if (!wal_frames && h.fileChangeCounter == h.versionValidFor && h.databaseSizePages > 0 &&
      static_cast<unsigned long long>(st.st_size) < static_cast<unsigned long long>(page) * h.databaseSizePages)
    throw file_error(path, "truncated or corrupted (the header promises " +
                               std::to_string(static_cast<unsigned long long>(page) * h.databaseSizePages) +
                               " bytes, the file has " + std::to_string(st.st_size) + ")");
  return true;
}

// What an SQLite error met while opening and checking a file says of it: a full disk or a failed
// read is not damage to the file.
const char* opening_failure(const SQLite::Exception& e) {
  switch (e.getErrorCode() & 0xff) {
    case SQLITE_FULL:
      return "no space left beside it (SQLite could not write its -wal or -shm file)";
    case SQLITE_IOERR:
      return "an input/output error on it or its -wal or -shm file (a full or failing disk?)";
    case SQLITE_CANTOPEN:
      return "cannot open it or its -wal or -shm file";
    case SQLITE_PERM:
    case SQLITE_AUTH:
      return "not permitted to open it";
    default:
      return "unreadable or corrupted";
  }
}

// Checks an open database is ours and readable. Returns false for an empty SQLite database.
bool check_schema(SQLite::Database& db, const std::string& path) {
  try {
    // One statement, so one read snapshot: read one by one, a process creating the schema at the
    // same instant could commit between the reads (application_id 0 but tables present).
    SQLite::Statement q(db,
                        "SELECT (SELECT application_id FROM pragma_application_id), "
                        "(SELECT user_version FROM pragma_user_version), (SELECT count(*) FROM sqlite_master)");
    q.executeStep();
    const int app = q.getColumn(0).getInt();
    const int version = q.getColumn(1).getInt();
    const int tables = q.getColumn(2).getInt();
    if (app == 0 && version == 0 && tables == 0) return false;
    if (app != kHistoryApplicationId)
      throw file_error(path,
                       "an SQLite database, but not a softdrop database (application_id " + std::to_string(app) + ")");
    if (version > kHistorySchemaVersion)
      throw file_error(path, "written by a newer softdrop (schema version " + std::to_string(version) +
                                 "; this build reads up to " + std::to_string(kHistorySchemaVersion) + ")");
    if (version < 1) throw file_error(path, "softdrop database without a schema version");
    // Every table of its version, before anything writes to it (a file with our id and version
    // but not our tables would otherwise be switched to WAL and then fail on the first query).
    for (const char* table : kTables) {
      if (version < 2 && std::string(table).rfind("sweep", 0) == 0) continue;  // version 2's tables
      if (version < 6 && std::string(table) == "validations") continue;        // version 6's
      SQLite::Statement t(db, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?");
      t.bind(1, table);
      t.executeStep();
      if (t.getColumn(0).getInt() == 0)
        throw file_error(path, "softdrop database (schema version " + std::to_string(version) + ") without its table " +
                                   table + " (damaged or edited file?)");
    }
    const std::string check = db.execAndGet("PRAGMA quick_check").getString();
    if (check != "ok") {
      std::string line = check;
      for (char& c : line)
        if (c == '\n') c = ';';
      throw file_error(path, "corrupted (quick_check: " + line + ")");
    }
    return true;
  } catch (const SQLite::Exception& e) {
    if ((e.getErrorCode() & 0xff) == SQLITE_READONLY) throw;  // validate() retries read-write
    throw file_error(path, std::string(opening_failure(e)) + " (" + e.what() + ")");
  }
}

}  // namespace

DatabaseError file_error(const std::string& path, const std::string& what) {
  return DatabaseError("--db '" + path + "': " + what);
}

void set_row_status(SQLite::Database& db, const char* table, std::int64_t id, const std::string& status,
                    const std::string& what) {
  SQLite::Statement u(db, std::string("UPDATE ") + table + " SET status = ?, updated = " + kNow + " WHERE id = ?");
  u.bind(1, status);
  u.bind(2, id);
  if (u.exec() != 1) throw std::runtime_error(what + " " + std::to_string(id) + ": no such " + what);
}

namespace {
bool exists(const std::string& path) { return file_size(path) >= 0; }

// `path` as an SQLite URI for an immutable file: read without locks or a -shm file.
std::string immutable_uri(const std::string& path) {
  std::string uri = "file:";
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#') {
      static const char* hex = "0123456789ABCDEF";
      uri += '%';
      uri += hex[static_cast<unsigned char>(c) >> 4];
      uri += hex[static_cast<unsigned char>(c) & 15];
    } else {
      uri += c;
    }
  }
  return uri + "?immutable=1";
}

// Opens a connection. A WAL-mode file is normally opened with its -shm and -wal files beside it,
// which SQLite creates if they are missing. A reader who cannot write the file must not create
// them: on read-only media it cannot, and in a shared folder they would belong to the reader, and
// the file's owner could no longer write past them. With no -shm, no WAL frames and no hot journal
// there is nothing to recover (no writer is at work), so such a reader reads the file as immutable.
std::unique_ptr<SQLite::Database> connect(const std::string& path, int flags) {
  if ((flags & SQLite::OPEN_CREATE) == 0 && exists(path)) {
    const bool wal_frames = file_size(path + "-wal") > 0;
    if (::access(path.c_str(), W_OK) != 0 && !exists(path + "-shm") && !wal_frames && !exists(path + "-journal"))
      return std::make_unique<SQLite::Database>(immutable_uri(path), SQLite::OPEN_READONLY | SQLite::OPEN_URI, 60'000);
  }
  return std::make_unique<SQLite::Database>(path, flags, 60'000);
}

// The read-only checks of open_database, run before anything may write to the file.
void validate(const std::string& path, OpenMode mode) {
  // SQLite reads "" as a temporary database, deleted on close: a whole run would vanish.
  if (path.empty()) throw file_error(path, "an empty file name");
  // Opening a WAL-mode file, even read-only, creates its -wal and -shm files; a refused file must
  // be left as it was found, so those made here are removed again.
  const bool had_wal = exists(path + "-wal"), had_shm = exists(path + "-shm");
  auto tidy = [&] {
    if (!had_wal && file_size(path + "-wal") == 0) ::unlink((path + "-wal").c_str());
    if (!had_shm && !exists(path + "-wal")) ::unlink((path + "-shm").c_str());
  };
  // Before SQLite reads the log: its recovery would drop what follows a damaged frame, and the next
  // writer would overwrite it.
  if (const std::string damage = wal_damage(read_wal(path + "-wal")); !damage.empty())
    throw file_error(path, "its write-ahead log '" + path + "-wal' is damaged: " + damage +
                               "; nothing was written. Copy both files aside; `sqlite3 '" + path +
                               "' 'PRAGMA wal_checkpoint'` keeps what precedes the damage and drops the rest");
  const bool has_content = check_file(path, mode);
  if (!has_content) return;
  // Inspect read-only first: nothing is written to a file that turns out not to be ours.
  bool ours = false;
  auto probe = [&](int flags) {
    auto db = connect(path, flags);
    ours = check_schema(*db, path);
  };
  try {
    try {
      probe(SQLite::OPEN_READONLY);
    } catch (const SQLite::Exception& e) {
      // A process killed inside a transaction of a rollback-journal file (a new file before it
      // switches to WAL, or one edited with sqlite3) leaves a hot journal, which a read-only
      // connection cannot roll back (SQLITE_READONLY_ROLLBACK; likewise _RECOVERY for a WAL
      // index). Rolling back restores the file's last committed state, which every SQLite
      // opener would do; the header check above already showed the file is SQLite.
      if ((e.getErrorCode() & 0xff) != SQLITE_READONLY || ::access(path.c_str(), W_OK) != 0) throw;
      probe(SQLite::OPEN_READWRITE);
    }
    if (!ours && mode == OpenMode::read_only) throw file_error(path, "empty SQLite database, no softdrop data");
  } catch (const SQLite::Exception& e) {
    tidy();
    throw file_error(path, std::string(opening_failure(e)) + " (" + e.what() + ")");
  } catch (...) {
    tidy();
    throw;
  }
}
}  // namespace

std::unique_ptr<SQLite::Database> open_database(const std::string& path, OpenMode mode) {
  validate(path, mode);
  if (mode == OpenMode::create && exists(path) && ::access(path.c_str(), W_OK) != 0)
    throw file_error(path, std::string("cannot write to it (") + std::strerror(errno) + ")");
  return guarded(path, [&] {
    // A reader of a checked, writable file still opens it read-write (and never writes): SQLite can
    // then checkpoint and remove the -wal and -shm files when the last connection closes, which a
    // read-only connection cannot.
    const int flags = mode == OpenMode::create            ? SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE
                      : ::access(path.c_str(), W_OK) == 0 ? SQLite::OPEN_READWRITE
                                                          : SQLite::OPEN_READONLY;
    auto db = connect(path, flags);
    db->exec("PRAGMA foreign_keys = ON");
    if (mode == OpenMode::read_only) return db;
    // Switching to WAL needs the file to itself and does not wait through the busy handler, so a
    // second process opening a new file at the same instant retries here.
    for (int attempt = 0;; ++attempt) {
      try {
        db->exec("PRAGMA journal_mode = WAL");
        break;
      } catch (const SQLite::Exception& e) {
        if ((e.getErrorCode() & 0xff) != SQLITE_BUSY || attempt >= 6000) throw;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
    // NORMAL in WAL mode: a killed process never loses a committed transaction; a power cut may
    // lose the last few, never consistency.
    db->exec("PRAGMA synchronous = NORMAL");
    SQLite::Transaction t(*db, SQLite::TransactionBehavior::IMMEDIATE);
    // Read again inside the write lock: another process may have created the schema meanwhile.
    const int version = db->execAndGet("PRAGMA user_version").getInt();
    if (version < 1) {
      db->exec(kSchemaV1);
      db->exec("PRAGMA application_id = " + std::to_string(kHistoryApplicationId));
    }
    if (version < 2) db->exec(kSchemaV2);  // migration 1 -> 2: the sweep tables
    // Migration 2 -> 3: the strategies' state (a column: added only where it is not already).
    if (version < 3 && !has_column(*db, "generations", "state")) db->exec(kSchemaV3);
    if (version < 5) {  // migrations 3 -> 4 -> 5: relocation moves, islands
      widen_generation_kinds(*db);
      add_island_columns(*db);
    }
    if (version < 6) db->exec(kSchemaV6);  // migration 5 -> 6: the held-out values
    if (version < 7)                       // migration 6 -> 7: the robust objectives' counts
      for (const AddedColumn& c : kSchemaV7) add_column(*db, c);
    if (version < 8) {  // migration 7 -> 8: candidates' moves, the kind 'mixed', the views
      if (version >= 1) widen_generation_kinds(*db);
      for (const AddedColumn& c : kSchemaV8) add_column(*db, c);
    }
    if (version < 9)  // migration 8 -> 9: sweep droplets' shaken_at and route_tortuosity
      for (const AddedColumn& c : kSchemaV9) add_column(*db, c);
    if (version < 10) {  // migration 9 -> 10: the pairs' second droplets, the views
      db->exec(kSchemaV10);
      db->exec(kViews);
    }
    if (version < kHistorySchemaVersion) db->exec("PRAGMA user_version = " + std::to_string(kHistorySchemaVersion));
    t.commit();
    return db;
  });
}

}  // namespace softdrop::detail

namespace softdrop {
void check_database(const std::string& path) { detail::validate(path, OpenMode::create); }
}  // namespace softdrop
