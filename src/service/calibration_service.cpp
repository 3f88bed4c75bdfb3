// A calibration scan (calibration_service.hpp): the settings in turn, each recorded as it ends,
// then ranked.
#include "service/calibration_service.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {

bool CalibrationScan::IsValid(std::string* why) const {
  using detail::fail;
  if (!calibration.IsValid(why)) return false;
  if (settings.empty()) return fail(why, "settings: none to run");
  if (!labels.empty() && labels.size() != settings.size())
    return fail(why,
                "labels: " + std::to_string(labels.size()) + " for " + std::to_string(settings.size()) + " settings");
  return detail::valid_threads(threads, why);
}

std::vector<CalibrationRow> run_calibration_scan(const CalibrationScan& scan, CalibrationObserver& observer) {
  std::string why;
  if (!scan.IsValid(&why)) throw std::invalid_argument(why);
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  std::vector<CalibrationRow> rows;
  for (std::size_t i = 0; i < scan.settings.size() && !observer.stop_requested(); ++i) {
    CalibrationRow row;
    row.setting = static_cast<int>(i);
    row.label = scan.labels.empty() ? std::string() : scan.labels[i];
    row.droplet = scan.settings[i];
    if (!row.droplet.IsValid(&row.refused)) {
      rows.push_back(std::move(row));
    } else {
      const auto s0 = clock::now();
      row.result = run_calibration(scan.calibration, row.droplet, scan.threads, [&](long done, long total) {
        observer.progress(row.setting, done, total, since(t0));
      });
      row.seconds = since(s0);
      rows.push_back(std::move(row));
    }
    if (!observer.finished(rows)) break;
  }
  std::stable_sort(rows.begin(), rows.end(), [](const CalibrationRow& x, const CalibrationRow& y) {
    if (x.refused.empty() != y.refused.empty()) return x.refused.empty();
    return x.result.score < y.result.score;
  });
  return rows;
}

}  // namespace softdrop
