#include "validation_rows.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "softdrop/version.hpp"
#include "sqlite_file.hpp"

namespace softdrop {

ValidationRecord validation_record(std::int64_t generation, const HeldOutOptions& options, const HeldOutValue& value) {
  ValidationRecord v;
  v.generation = generation;
  v.version = kVersion;
  v.seed = options.seed;
  v.starts = options.starts;
  const HeldOutRuns& a = value.at_dt;
  v.dt = a.dt, v.passed = a.passed, v.mean_t = a.mean_t, v.standard_error = a.standard_error;
  v.q1 = a.q1, v.median = a.median, v.q3 = a.q3;
  v.half_dt = options.half_dt;
  if (v.half_dt) {
    v.half_dt_passed = value.at_half_dt.passed, v.half_dt_mean_t = value.at_half_dt.mean_t;
    v.half_dt_standard_error = value.at_half_dt.standard_error;
    v.paired = value.paired, v.dt_shift = value.dt_shift, v.dt_shift_error = value.dt_shift_error;
  }
  return v;
}

namespace detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A number, or NULL where it is NaN (nothing passed).
std::optional<double> finite(double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; }
double real_or_nan(const SQLite::Column& c) { return c.isNull() ? kNaN : as_real(c); }

}  // namespace

void insert_validation(SQLite::Database& db, std::int64_t run, const ValidationRecord& v) {
  SQLite::Statement q(db, std::string("INSERT OR REPLACE INTO validations (run_id, generation, seed, starts, created, "
                                      "version, dt, passed, mean_t, standard_error, q1, median, q3, half_dt, "
                                      "half_dt_passed, half_dt_mean_t, half_dt_standard_error, paired, dt_shift, "
                                      "dt_shift_error) VALUES (?, ?, ?, ?, ") +
                              kNow + ", ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  const bool h = v.half_dt;
  insert_row(q, run, v.generation, static_cast<std::int64_t>(v.seed), v.starts, v.version, v.dt, v.passed,
             finite(v.mean_t), finite(v.standard_error), finite(v.q1), finite(v.median), finite(v.q3), h ? 1 : 0,
             value_if(h, v.half_dt_passed), h ? finite(v.half_dt_mean_t) : std::nullopt,
             h ? finite(v.half_dt_standard_error) : std::nullopt, value_if(h, v.paired),
             h ? finite(v.dt_shift) : std::nullopt, h ? finite(v.dt_shift_error) : std::nullopt);
}

std::vector<ValidationRecord> read_validations(SQLite::Database& db, std::int64_t run) {
  SQLite::Statement q(db,
                      "SELECT generation, seed, starts, created, version, dt, passed, mean_t, standard_error, q1, "
                      "median, q3, half_dt, half_dt_passed, half_dt_mean_t, half_dt_standard_error, paired, "
                      "dt_shift, dt_shift_error FROM validations WHERE run_id = ? ORDER BY generation, seed, starts");
  q.bind(1, run);
  std::vector<ValidationRecord> out;
  while (q.executeStep()) {
    ValidationRecord v;
    v.generation = as_int64(q.getColumn(0));
    v.seed = static_cast<std::uint64_t>(as_int64(q.getColumn(1)));
    v.starts = as_int(q.getColumn(2));
    v.created = as_text(q.getColumn(3));
    v.version = as_text(q.getColumn(4));
    v.dt = as_real(q.getColumn(5));
    v.passed = as_int(q.getColumn(6));
    v.mean_t = real_or_nan(q.getColumn(7));
    v.standard_error = real_or_nan(q.getColumn(8));
    v.q1 = real_or_nan(q.getColumn(9));
    v.median = real_or_nan(q.getColumn(10));
    v.q3 = real_or_nan(q.getColumn(11));
    v.half_dt = as_int(q.getColumn(12)) != 0;
    if (v.half_dt) {
      v.half_dt_passed = as_int(q.getColumn(13));
      v.half_dt_mean_t = real_or_nan(q.getColumn(14));
      v.half_dt_standard_error = real_or_nan(q.getColumn(15));
      v.paired = as_int(q.getColumn(16));
      v.dt_shift = real_or_nan(q.getColumn(17));
      v.dt_shift_error = real_or_nan(q.getColumn(18));
    }
    if (v.passed < 0 || v.passed > v.starts || !(v.dt > 0))
      throw std::runtime_error("run " + std::to_string(run) + ": a validation of generation " +
                               std::to_string(v.generation) + " holds " + std::to_string(v.passed) + " of " +
                               std::to_string(v.starts) + " passed at dt " + std::to_string(v.dt) +
                               " (damaged or edited file?)");
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace detail
}  // namespace softdrop
