// Sweep records (SweepStore) on a softdrop SQLite database (see sqlite_file.hpp).
#include <SQLiteCpp/SQLiteCpp.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "softdrop/store.hpp"
#include "softdrop/version.hpp"
#include "sqlite_file.hpp"

namespace softdrop {
namespace {
using detail::kNow;

class SqliteSweepStore final : public SweepStore, private detail::SqliteConnection {
 public:
  SqliteSweepStore(const std::string& path, OpenMode mode) : SqliteConnection(path, mode) {}

  std::int64_t find(const std::string& params) override {
    return guarded([&] { return find_id(params); });
  }

  std::int64_t find_or_create(const std::string& params, const SweepOptions& o) override {
    return guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::IMMEDIATE);
      std::int64_t id = find_id(params);
      if (id == 0) {
        SQLite::Statement q(db_, std::string("INSERT INTO sweeps (created, updated, version, status, params, units) "
                                             "VALUES (") +
                                     kNow + ", " + kNow + ", ?, 'running', ?, ?)");
        detail::insert_row(q, kVersion, params, static_cast<std::int64_t>(o.porosities.size()) * o.media);
        id = db_.getLastInsertRowid();
      }
      t.commit();
      return id;
    });
  }

  std::vector<SweepUnit> done_units(std::int64_t sweep) override {
    return guarded([&] {
      std::vector<SweepUnit> out;
      SQLite::Statement q(db_,
                          "SELECT porosity_index, medium_index FROM sweep_media WHERE sweep_id = ? "
                          "ORDER BY porosity_index, medium_index");
      q.bind(1, sweep);
      while (q.executeStep()) out.push_back({detail::as_int(q.getColumn(0)), detail::as_int(q.getColumn(1))});
      return out;
    });
  }

  bool has_unit(std::int64_t sweep, const SweepUnit& unit) override {
    return guarded([&] { return stored(sweep, unit); });
  }

  bool add(std::int64_t sweep, const SweepMedium& m) override {
    return guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::IMMEDIATE);
      if (stored(sweep, m.unit)) return false;  // read inside the write lock: no other writer now
      SQLite::Statement q(db_,
                          "INSERT INTO sweep_media (sweep_id, porosity_index, medium_index, target_porosity, "
                          "porosity, grains, medium_seed, droplets, passed, stuck, timeout, diverged, mean_t, "
                          "standard_error, stuck_fraction, seconds) "
                          "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
      detail::insert_row(q, sweep, m.unit.porosity, m.unit.medium, m.target_porosity, m.porosity, m.grains,
                         static_cast<std::int64_t>(m.medium_seed), static_cast<int>(m.droplets.size()), m.passed,
                         m.stuck, m.timeout, m.diverged, detail::value_if(m.passed > 0, m.mean_t),
                         detail::value_if(m.passed > 1, m.standard_error), m.stuck_fraction, m.seconds);
      SQLite::Statement d(db_,
                          "INSERT INTO sweep_droplets (sweep_id, porosity_index, medium_index, droplet, start_x, "
                          "outcome, tortuosity, steps, shaken_at, route_tortuosity) "
                          "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
      for (const SweepDroplet& r : m.droplets)
        detail::insert_row(d, sweep, m.unit.porosity, m.unit.medium, r.droplet, r.start_x, to_string(r.outcome),
                           detail::value_if(r.outcome == Outcome::passed, r.tortuosity), r.steps,
                           detail::value_if(!std::isnan(r.shaken_at), r.shaken_at),
                           detail::value_if(!std::isnan(r.route_tortuosity), r.route_tortuosity));
      if (!m.second_droplets.empty()) {
        SQLite::Statement p(
            db_,
            "INSERT INTO sweep_second_droplets (sweep_id, porosity_index, medium_index, droplet, start_x, "
            "outcome, tortuosity, steps, shaken_at, route_tortuosity, released_at, first_held_at, "
            "held_at, contact_steps, shared_touched) "
            "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
        for (const SweepSecond& s : m.second_droplets) {
          const SweepDroplet& r = s.run;
          detail::insert_row(p, sweep, m.unit.porosity, m.unit.medium, r.droplet, r.start_x, to_string(r.outcome),
                             detail::value_if(r.outcome == Outcome::passed, r.tortuosity), r.steps,
                             detail::value_if(!std::isnan(r.shaken_at), r.shaken_at),
                             detail::value_if(!std::isnan(r.route_tortuosity), r.route_tortuosity), s.released_at,
                             detail::value_if(!std::isnan(s.first_held_at), s.first_held_at),
                             detail::value_if(!std::isnan(s.held_at), s.held_at), s.contact_steps, s.shared_touched);
        }
      }
      SQLite::Statement u(db_, std::string("UPDATE sweeps SET updated = ") + kNow + " WHERE id = ?");
      u.bind(1, sweep);
      u.exec();
      t.commit();
      return true;
    });
  }

  void set_status(std::int64_t sweep, const std::string& status) override {
    guarded([&] {
      detail::set_row_status(db_, "sweeps", sweep, status, "sweep");
      return 0;
    });
  }

  std::vector<SweepRecord> sweeps() override {
    return guarded(
        [&] { return detail::read_rows(db_, std::string(kColumns) + " GROUP BY s.id ORDER BY s.id", read); });
  }

  SweepRecord sweep(std::int64_t id) override {
    return guarded([&] {
      return detail::read_row(db_, std::string(kColumns) + " WHERE s.id = ? GROUP BY s.id", id, "sweep", path_, read);
    });
  }

  std::vector<SweepMedium> media(std::int64_t sweep_id) override {
    return guarded([&] { return read_media(sweep_id, nullptr); });
  }

  std::optional<SweepMedium> medium(std::int64_t sweep_id, const SweepUnit& unit) override {
    return guarded([&] {
      std::vector<SweepMedium> one = read_media(sweep_id, &unit);
      return one.empty() ? std::optional<SweepMedium>() : std::optional<SweepMedium>(std::move(one.front()));
    });
  }

 private:
  // The sweep's stored media with their droplets, in unit order: all, or the one of `only`.
  std::vector<SweepMedium> read_media(std::int64_t sweep_id, const SweepUnit* only) {
    sweep(sweep_id);
    SQLite::Transaction t(db_, SQLite::TransactionBehavior::DEFERRED);  // one consistent snapshot
    const std::string where =
        std::string(" WHERE sweep_id = ?") + (only ? " AND porosity_index = ? AND medium_index = ?" : "");
    const auto bind = [&](SQLite::Statement& q) {
      q.bind(1, sweep_id);
      if (only) q.bind(2, only->porosity), q.bind(3, only->medium);
    };
    std::vector<SweepMedium> out;
    SQLite::Statement q(db_,
                        "SELECT porosity_index, medium_index, target_porosity, porosity, grains, medium_seed, "
                        "passed, stuck, timeout, diverged, mean_t, standard_error, stuck_fraction, seconds "
                        "FROM sweep_media" +
                            where + " ORDER BY porosity_index, medium_index");
    bind(q);
    while (q.executeStep()) {
      SweepMedium m;
      m.unit = {detail::as_int(q.getColumn(0)), detail::as_int(q.getColumn(1))};
      m.target_porosity = detail::as_real(q.getColumn(2));
      m.porosity = detail::as_real(q.getColumn(3));
      m.grains = detail::as_int(q.getColumn(4));
      m.medium_seed = static_cast<std::uint64_t>(detail::as_int64(q.getColumn(5)));
      m.passed = detail::as_int(q.getColumn(6));
      m.stuck = detail::as_int(q.getColumn(7));
      m.timeout = detail::as_int(q.getColumn(8));
      m.diverged = detail::as_int(q.getColumn(9));
      m.mean_t = q.getColumn(10).isNull() ? 0.0 : detail::as_real(q.getColumn(10));
      m.standard_error = q.getColumn(11).isNull() ? 0.0 : detail::as_real(q.getColumn(11));
      m.stuck_fraction = detail::as_real(q.getColumn(12));
      m.seconds = detail::as_real(q.getColumn(13));
      out.push_back(std::move(m));
    }
    SQLite::Statement d(db_, std::string("SELECT porosity_index, medium_index, droplet, start_x, outcome, tortuosity, "
                                         "steps, ") +
                                 // A file older than version 9, read as it is, has not these columns.
                                 (detail::has_column(db_, "sweep_droplets", "shaken_at") ? "shaken_at, route_tortuosity"
                                                                                         : "NULL, NULL") +
                                 " FROM sweep_droplets" + where + " ORDER BY porosity_index, medium_index, droplet");
    bind(d);
    std::size_t k = 0;
    while (d.executeStep()) medium_of(out, &k, d, sweep_id, "droplets").droplets.push_back(droplet_row(d));
    if (db_.tableExists("sweep_second_droplets")) {  // none before version 10
      SQLite::Statement p(db_,
                          "SELECT porosity_index, medium_index, droplet, start_x, outcome, tortuosity, steps, "
                          "shaken_at, route_tortuosity, released_at, first_held_at, held_at, contact_steps, "
                          "shared_touched FROM sweep_second_droplets" +
                              where + " ORDER BY porosity_index, medium_index, droplet");
      bind(p);
      read_second_droplets(p, sweep_id, out);
    }
    t.commit();
    return out;
  }

  // The record of the unit in a row's first two columns (porosity_index, medium_index), looked
  // for from media[*k] on: rows and media are both in unit order.
  static SweepMedium& medium_of(std::vector<SweepMedium>& media, std::size_t* k, SQLite::Statement& row,
                                std::int64_t sweep_id, const char* what) {
    const SweepUnit u{detail::as_int(row.getColumn(0)), detail::as_int(row.getColumn(1))};
    while (*k < media.size() && !(media[*k].unit == u)) ++*k;
    if (*k == media.size())
      throw std::runtime_error("sweep " + std::to_string(sweep_id) + ": " + what + " of porosity " +
                               std::to_string(u.porosity) + " medium " + std::to_string(u.medium) +
                               " without their medium, or out of order (damaged or edited file?)");
    return media[*k];
  }

  static double real_or_nan(SQLite::Statement& row, int c) {
    return row.getColumn(c).isNull() ? std::numeric_limits<double>::quiet_NaN() : detail::as_real(row.getColumn(c));
  }

  // A droplet from columns 2 to 8: droplet, start_x, outcome, tortuosity, steps, shaken_at, route_tortuosity.
  static SweepDroplet droplet_row(SQLite::Statement& row) {
    return {detail::as_int(row.getColumn(2)),
            detail::as_real(row.getColumn(3)),
            parse_outcome(detail::as_text(row.getColumn(4))),
            row.getColumn(5).isNull() ? 0.0 : detail::as_real(row.getColumn(5)),
            detail::as_int64(row.getColumn(6)),
            real_or_nan(row, 7),
            real_or_nan(row, 8)};
  }

  // The pairs' seconds, the rows of `d`, into their media's records (`media` in unit order).
  static void read_second_droplets(SQLite::Statement& d, std::int64_t sweep_id, std::vector<SweepMedium>& media) {
    std::size_t k = 0;
    while (d.executeStep()) {
      SweepMedium& m = medium_of(media, &k, d, sweep_id, "second droplets");
      SweepSecond s;
      s.run = droplet_row(d);
      s.released_at = detail::as_real(d.getColumn(9));
      s.first_held_at = real_or_nan(d, 10), s.held_at = real_or_nan(d, 11);
      s.contact_steps = detail::as_int64(d.getColumn(12));
      s.shared_touched = detail::as_int(d.getColumn(13));
      m.second_droplets.push_back(s);
    }
  }

  static constexpr const char* kColumns =
      "SELECT s.id, s.created, s.updated, s.version, s.status, s.params, s.units, count(m.sweep_id) "
      "FROM sweeps s LEFT JOIN sweep_media m ON m.sweep_id = s.id";

  std::int64_t find_id(const std::string& params) {
    SQLite::Statement q(db_, "SELECT id FROM sweeps WHERE params = ?");
    q.bind(1, params);
    return q.executeStep() ? detail::as_int64(q.getColumn(0)) : 0;
  }

  bool stored(std::int64_t sweep, const SweepUnit& unit) {
    SQLite::Statement q(db_,
                        "SELECT 1 FROM sweep_media WHERE sweep_id = ? AND porosity_index = ? AND medium_index = ?");
    q.bind(1, sweep);
    q.bind(2, unit.porosity);
    q.bind(3, unit.medium);
    return q.executeStep();
  }

  static SweepRecord read(SQLite::Statement& q) {
    SweepRecord r;
    detail::read_row_head(q, &r);
    r.units = detail::as_int64(q.getColumn(6));
    r.done = detail::as_int64(q.getColumn(7));
    if (r.units < 1 || r.done > r.units)
      throw std::runtime_error("sweep " + std::to_string(r.id) + ": column units holds " + std::to_string(r.units) +
                               " with " + std::to_string(r.done) + " media stored (damaged or edited file?)");
    return r;
  }
};

}  // namespace

std::unique_ptr<SweepStore> open_sweep_store(const std::string& path, OpenMode mode) {
  return std::make_unique<SqliteSweepStore>(path, mode);
}

}  // namespace softdrop
