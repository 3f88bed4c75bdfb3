#pragma once
// A sweep across the ranks of an MPI job. Rank 0 owns the store: it hands out the units one at a
// time as ranks ask for them (so a rank on slow, dense media simply asks less often), commits
// each record as it arrives, one transaction a unit, and runs units itself. The other ranks hold
// no database: they compute the units they are given and send the records to rank 0. A unit's
// record does not depend on the rank, threads or order, so the store equals a one-process one.

#include <functional>
#include <vector>

#include "cli/mpi_job.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop::cli {

/// Rank 0's part: `todo` (the units the store lacks) handed out across the job, this rank's own
/// share run on `threads` threads. `on_done` gets every rank's records (on this rank's threads,
/// one at a time), as run_sweep_units' does. `stop` once true hands out no more units; the units
/// given out are finished and committed. `stored(unit)` is asked before a unit is handed out:
/// true passes it over (another process stored it meanwhile). Returns when every rank is done.
struct RanksReport {
  std::vector<int> ran;      ///< units each rank ran
  double serve_seconds = 0;  ///< rank 0's time answering the other ranks and storing their records
};
RanksReport run_sweep_units_on_ranks(const Job& job, const SweepOptions& options, const std::vector<SweepUnit>& todo,
                                     int threads, const std::function<void(SweepMedium&&)>& on_done,
                                     const std::function<bool()>& stop,
                                     const std::function<bool(const SweepUnit&)>& stored);

/// The part of any other rank: the units rank 0 hands it, on `threads` threads.
void work_on_sweep_units(const Job& job, const SweepOptions& options, int threads);

}  // namespace softdrop::cli
