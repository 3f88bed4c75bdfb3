#pragma once
// A calibration scan as the program runs it (`softdrop calibrate`): each setting's small sweep and
// area traces in turn (studies/calibration.hpp), an observer that hears each droplet and each
// setting and may stop the scan between settings, and the settings ranked by score. Private to the
// library, as the calibration's types are.

#include <string>
#include <vector>

#include "studies/calibration.hpp"

namespace softdrop {

/// What a scan runs: `settings` (labels[i] says how setting i was made; empty: none), each on the
/// same calibration, with `threads` threads (0: all cores; the numbers do not depend on it).
struct CalibrationScan {
  CalibrationOptions calibration;
  std::vector<DropletParams> settings;
  std::vector<std::string> labels;
  int threads = 0;

  /// The calibration's options, at least one setting, labels empty or one a setting, threads in
  /// [0, 4096]. A setting the droplet's limits refuse is not invalid: it is recorded as refused.
  bool IsValid(std::string* why) const;
};

/// One setting's row: its figures, or why the droplet's limits refuse it.
struct CalibrationRow {
  int setting = 0;
  std::string label;
  DropletParams droplet;
  std::string refused;  ///< empty unless refused; then `result` is empty
  CalibrationResult result;
  double seconds = 0;  ///< wall time of the setting
};

/// What a scan tells as it goes, on the thread that called run_calibration_scan.
class CalibrationObserver {
 public:
  virtual ~CalibrationObserver() = default;
  /// Droplets of setting `setting` done of its `total`; `seconds` since the scan began.
  virtual void progress(int /*setting*/, long /*done*/, long /*total*/, double /*seconds*/) {}
  /// After each setting, with every row so far in the order of the settings. false stops the scan
  /// there (no setting after it runs).
  virtual bool finished(const std::vector<CalibrationRow>& /*rows*/) { return true; }
  /// Asked before each setting: true stops the scan as finished() returning false does.
  virtual bool stop_requested() { return false; }
};

/// Runs the settings of `scan` in order until they are done or the observer stops the scan, and
/// returns their rows ranked: the settings that ran by score (lowest first, ties in setting
/// order), then the refused ones. Throws std::invalid_argument for invalid options.
std::vector<CalibrationRow> run_calibration_scan(const CalibrationScan& scan, CalibrationObserver& observer);

}  // namespace softdrop
