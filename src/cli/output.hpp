#pragma once
// Output helpers shared by the CLI commands: checked output paths, progress on stderr.

#include <atomic>
#include <chrono>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "studies/area_trace.hpp"

namespace softdrop::cli {

/// Throws std::runtime_error naming `option` if `path` cannot be created (missing directory,
/// or a directory itself). Called before any long work so that a bad path fails fast.
void check_output_path(const std::string& option, const std::string& path);

/// check_output_path for a picture, and its extension names a format render can write.
void check_picture_path(const std::string& option, const std::string& path);

/// "P %, ETA S s" for `done` of `total` after `elapsed` seconds (the rest at the pace so far).
std::string percent_and_eta(double elapsed, double done, double total);

/// Throttled progress line on stderr ("label: done/total (P %, ETA S s)"): on a terminal one line
/// updated in place about once a second, in a pipe a plain line every 10 s; always the last item.
class Progress {
 public:
  explicit Progress(std::string label);
  void update(long done, long total);

 private:
  std::string label_;
  std::chrono::steady_clock::time_point t0_, last_;
  bool tty_;
};

/// Makes SIGINT, SIGTERM and SIGHUP remove the temporary files of unfinished outputs before they
/// end the program (see temp_files.hpp). Called once at start.
void remove_temp_files_on_signals();

/// While alive, SIGINT and SIGTERM raise a stop flag (the command finishes the unit in flight and
/// stops cleanly) and print `message`; a second signal exits at once with code 128 + the signal.
/// The previous handlers are restored on destruction. One at a time.
class StopOnSignal {
 public:
  explicit StopOnSignal(const char* message);
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  bool requested() const;
  /// The exit code of a stopped command: 130 after SIGINT, 143 after SIGTERM; 0 without a signal.
  int exit_code() const;
  const std::atomic<bool>* flag() const;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

/// Rows of cells printed as an aligned table (doubles to 8 digits), CSV or a JSON array of objects
/// (both with every digit).
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<nlohmann::json>> rows;
  /// format: table, csv or json.
  void print(std::ostream& out, const std::string& format) const;
  /// The CSV form, written atomically to `path` (temporary file, then rename).
  void write_csv(const std::string& path) const;
};

/// Writes area traces as one CSV (atomically): droplet, t (time units), area (length units
/// squared), area_ratio (S / S0, S0 the droplet's area when it reached the medium; empty if it
/// never did), phase (above: before its lowest mass reached y = H; inside; below: after its highest
/// mass left y = 0). Droplet i is traces[i].
void write_area_traces(const std::string& path, const std::vector<AreaTrace>& traces);

/// A JSON number, or null where `v` is not finite (a mean or error of nothing that passed).
nlohmann::json finite_or_null(double v);

/// Formats a double with the given significant digits (17 = round trip).
std::string fmt(double v, int digits = 17);  // 17 and more: the shortest that reads back the same

/// v with `places` decimals ("1.5000", not "1.5"), as std::fixed writes it.
std::string fixed(double v, int places);
/// "value ± error" at the error's precision: the error to two significant digits and the value to
/// the same decimal place (1.5751 ± 0.0129 -> "1.575 ± 0.013"; 3.89 ± 0.19 -> "3.89 ± 0.19").
/// A non-finite or zero error gives the value to 4 significant digits and the error as is.
std::string with_error(double value, double error);

}  // namespace softdrop::cli
