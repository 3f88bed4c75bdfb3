// One droplet of a stored sweep, as the sweep ran it: what softdrop.sweep_droplet and
// `softdrop simulate --from-sweep` run again.
#pragma once

#include <cstdint>
#include <string>

#include "softdrop/store.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {

struct StoredSweepDroplet {
  std::int64_t sweep = 0;
  SweepOptions options;  ///< the sweep's: its droplet (options.droplet) and exit options (options.run)
  MediumOptions medium;  ///< generate_medium(medium) gives the droplet's medium again
  double porosity = 0;   ///< that medium's exact porosity, as stored
  SweepDroplet droplet;  ///< its start (start_x) and what the sweep stored of it
};

/// Droplet `droplet` of medium `medium_index` of porosity `porosity_index` of sweep `sweep` in
/// `store` (the file `db`, for messages). Throws std::invalid_argument naming an index out of the
/// sweep's range, a medium not stored yet, or a sweep of pairs (whose first droplets do not run
/// alone); DatabaseError for a stored medium its parameters would not give again.
StoredSweepDroplet stored_sweep_droplet(SweepStore& store, const std::string& db, std::int64_t sweep,
                                        int porosity_index, int medium_index, int droplet);

}  // namespace softdrop
