#pragma once
// The runs, generations and candidates tables' rows (internal to the store): a run's row, and its
// generations read back with their candidates, from files of every schema version.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <string>
#include <vector>

#include "softdrop/store.hpp"

namespace softdrop::detail {

/// "SELECT ... FROM runs" with the columns read_run reads, for a file of schema `version` (before
/// 5: no island columns; before 7: no droplets column, read as the evaluations).
std::string select_runs(int version);
/// A row of select_runs. Throws std::runtime_error for a value no run of softdrop stores (a damaged
/// or edited file is refused, not shown or resumed from).
RunRecord read_run(SQLite::Statement& q);

/// The run's generations from 0, each with its candidates, in the caller's read transaction;
/// `version` is the file's schema version (older files lack later columns). Throws
/// std::runtime_error for a missing generation, a candidate of none, or a generation without
/// candidates (a damaged or edited file).
std::vector<GenerationRecord> read_generations(SQLite::Database& db, std::int64_t run_id, int version);

}  // namespace softdrop::detail
