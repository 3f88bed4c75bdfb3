#pragma once
/// \file sweep_store.hpp
/// Where sweep records live: one storage interface, implemented on the same SQLite file family as
/// the search history (tables sweeps, sweep_media, sweep_droplets; see README.md). A medium and
/// its droplets are written in one transaction, so an interrupted sweep loses at most the medium
/// in flight and continues where it stopped.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "softdrop/open_mode.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {

/// A sweep's row.
struct SweepRecord {
  std::int64_t id = 0;
  std::string created, updated, version, status;
  std::string params;      ///< JSON of the options (the sweep's identity)
  std::int64_t units = 0;  ///< porosities x media
  std::int64_t done = 0;   ///< media stored
};

class SweepStore {
 public:
  virtual ~SweepStore() = default;
  /// The id of the sweep with exactly these parameters, 0 if there is none. Writes nothing.
  virtual std::int64_t find(const std::string& params_json) = 0;
  /// The id of the sweep with exactly these parameters, created if there is none.
  virtual std::int64_t find_or_create(const std::string& params_json, const SweepOptions& options) = 0;
  /// Units already stored for a sweep.
  virtual std::vector<SweepUnit> done_units(std::int64_t sweep) = 0;
  /// Stores one medium with its droplets in one transaction. Returns false, storing nothing, if
  /// the unit is already stored: another process running the same sweep computed it (records are
  /// deterministic, so they are the same).
  virtual bool add(std::int64_t sweep, const SweepMedium& medium) = 0;
  /// Whether the unit is stored (by this process or another one).
  virtual bool has_unit(std::int64_t sweep, const SweepUnit& unit) = 0;
  /// running, complete or interrupted.
  virtual void set_status(std::int64_t sweep, const std::string& status) = 0;
  virtual std::vector<SweepRecord> sweeps() = 0;
  /// Throws std::runtime_error naming the id if there is no such sweep.
  virtual SweepRecord sweep(std::int64_t id) = 0;
  /// Every stored medium of a sweep with its droplets, ordered by (porosity, medium).
  virtual std::vector<SweepMedium> media(std::int64_t sweep) = 0;
};

/// Opens the sweep store of a softdrop database (the same checks as open_history).
std::unique_ptr<SweepStore> open_sweep_store(const std::string& path, OpenMode mode);

}  // namespace softdrop
