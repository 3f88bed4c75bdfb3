#pragma once
// The validations table's rows (internal to the store): a held-out value written and read back.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <vector>

#include "softdrop/store.hpp"

namespace softdrop::detail {

/// Inserts (or replaces) `v` for `run`, in the caller's transaction.
void insert_validation(SQLite::Database& db, std::int64_t run, const ValidationRecord& v);
/// The run's rows, by generation, seed and starts.
std::vector<ValidationRecord> read_validations(SQLite::Database& db, std::int64_t run);

}  // namespace softdrop::detail
