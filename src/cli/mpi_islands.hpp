#pragma once
// Islands across the ranks of an MPI job: island i runs on rank i mod P. Rank 0 holds the
// history: between migrations every rank runs its islands, then sends their generations to rank
// 0, which stores them; at a migration rank 0 hands each island its immigrant, the ranks make the
// migration generations and rank 0 stores them together. Islands are independent between
// migrations, so the history equals the one the islands make on the threads of one process.

#include <vector>

#include "cli/mpi_job.hpp"
#include "optimizer/islands.hpp"

namespace softdrop::cli {

/// Rank 0's part: `islands` (all K of them, as made or resumed) run as drive_islands runs them,
/// with the callbacks called on this thread: a remote island's generations when its rank sends
/// them, after each stretch between migrations. Stops (options.stop, time limit, a callback) are
/// honoured at the next migration or the end of such a stretch.
SearchSummary drive_islands_on_ranks(const Job& job, std::vector<Search>& islands, const IslandOptions& island_options,
                                     const DriveOptions& options, const IslandCallbacks& callbacks);

/// Any other rank's part: the islands rank 0 gives it, on `threads` threads.
void work_on_islands(const Job& job, int threads, int lanes, bool speculate);

}  // namespace softdrop::cli
