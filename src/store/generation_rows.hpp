#pragma once
// The generations and candidates tables' rows (internal to the store): a run's generations read
// back with their candidates, from files of every schema version.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <vector>

#include "softdrop/history.hpp"

namespace softdrop::detail {

/// The run's generations from 0, each with its candidates, in the caller's read transaction;
/// `version` is the file's schema version (older files lack later columns). Throws
/// std::runtime_error for a missing generation, a candidate of none, or a generation without
/// candidates (a damaged or edited file).
std::vector<GenerationRecord> read_generations(SQLite::Database& db, std::int64_t run_id, int version);

}  // namespace softdrop::detail
