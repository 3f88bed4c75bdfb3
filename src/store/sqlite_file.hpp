#pragma once
// Opening a softdrop database (internal to the store): the checks made before anything writes to
// the file, WAL and foreign keys, and the schema, created or migrated to the current version.
// The schema is documented in README.md ("The database"); keep the two in step.

#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "softdrop/store.hpp"

namespace softdrop::detail {

/// SQL for "now" in UTC, ISO 8601 with milliseconds.
inline constexpr const char* kNow = "strftime('%Y-%m-%dT%H:%M:%fZ', 'now')";

/// Whether `table` has `column`: a file of an older version, read as it is, may lack one.
bool has_column(SQLite::Database& db, const char* table, const char* column);

/// One line naming the database file.
DatabaseError file_error(const std::string& path, const std::string& what);

/// Checks the file (read-only), then opens it. In create mode a missing file is created and the
/// schema is created or migrated to kHistorySchemaVersion. Throws std::runtime_error (one line
/// naming the file) for anything that is not a readable softdrop database.
std::unique_ptr<SQLite::Database> open_database(const std::string& path, OpenMode mode);

/// Sets `status` and `updated` of row `id` of `table` (runs or sweeps); throws naming `what` if
/// there is no such row.
void set_row_status(SQLite::Database& db, const char* table, std::int64_t id, const std::string& status,
                    const std::string& what);

/// Typed reads of a column: a value of another SQLite type (text or a blob where a number belongs,
/// as in a damaged or hand-edited file) throws std::runtime_error naming the column instead of
/// being converted silently (text would read as 0).
double as_real(const SQLite::Column& c);         ///< INTEGER or REAL
std::int64_t as_int64(const SQLite::Column& c);  ///< INTEGER
int as_int(const SQLite::Column& c);             ///< INTEGER that fits an int
std::string as_text(const SQLite::Column& c);    ///< TEXT

/// The columns every run and every sweep row begins with, columns 0 to 5 of `q` in this order: id,
/// created, updated, version, status, params; read into the record's fields of the same names.
template <class Record>
void read_row_head(SQLite::Statement& q, Record* r) {
  r->id = as_int64(q.getColumn(0));
  r->created = as_text(q.getColumn(1));
  r->updated = as_text(q.getColumn(2));
  r->version = as_text(q.getColumn(3));
  r->status = as_text(q.getColumn(4));
  r->params = as_text(q.getColumn(5));
}

/// Every row `select` gives, each made a record by read(q).
template <class Read>
auto read_rows(SQLite::Database& db, const std::string& select, Read read) {
  std::vector<decltype(read(std::declval<SQLite::Statement&>()))> out;
  SQLite::Statement q(db, select);
  while (q.executeStep()) out.push_back(read(q));
  return out;
}

/// The row `select` (whose one parameter is the id) gives for `id`, made a record by read(q).
/// Without one, throws naming the option and the file: "--run 7: no such run in 'a.db'" for
/// `what` = "run".
template <class Read>
auto read_row(SQLite::Database& db, const std::string& select, std::int64_t id, const std::string& what,
              const std::string& path, Read read) {
  SQLite::Statement q(db, select);
  q.bind(1, id);
  if (!q.executeStep())
    throw std::runtime_error("--" + what + " " + std::to_string(id) + ": no such " + what + " in '" + path + "'");
  return read(q);
}

/// `value` where `present`, else SQL NULL, for insert_row.
template <class T>
std::optional<T> value_if(bool present, const T& value) {
  return present ? std::optional<T>(value) : std::nullopt;
}

/// Binds `values` to the parameters of `q` in order (an empty std::optional as NULL) and runs it,
/// after resetting it and its bindings, so one statement can insert row after row.
template <class... Values>
void insert_row(SQLite::Statement& q, const Values&... values) {
  q.reset();
  q.clearBindings();
  int index = 0;
  const auto bind = [&](const auto& v) {
    ++index;
    if constexpr (requires { v.has_value(); }) {
      if (v.has_value()) q.bind(index, *v);
    } else {
      q.bind(index, v);
    }
  };
  (bind(values), ...);
  q.exec();
}

/// Runs f, turning its errors (SQLite's, and damaged contents found while reading) into one line
/// naming the file.
template <class F>
auto guarded(const std::string& path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const SQLite::Exception& e) {
    throw file_error(path, e.what());
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find(path) != std::string::npos) throw;
    throw file_error(path, e.what());
  } catch (const std::invalid_argument& e) {  // a stored name no parse knows
    throw file_error(path, e.what());
  }
}

/// The connection part of each store: the checked, open database and error translation.
class SqliteConnection {
 protected:
  SqliteConnection(const std::string& path, OpenMode mode)
      : path_(path), db_ptr_(open_database(path, mode)), db_(*db_ptr_) {}
  template <class F>
  auto guarded(F&& f) -> decltype(f()) {
    return detail::guarded(path_, std::forward<F>(f));
  }

  std::string path_;
  std::unique_ptr<SQLite::Database> db_ptr_;
  SQLite::Database& db_;
};

}  // namespace softdrop::detail
