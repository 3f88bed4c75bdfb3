#pragma once
/// \file calibration.hpp
/// Calibrating the droplet's free parameters (m, N, R, nRT, k_c, c_c, nu, ...) against the paper.
/// Each setting runs a small tortuosity-porosity sweep on overlapping media and a few area traces
/// through a non-overlapping phi = 0.79 medium, and is scored by how far its <T>(phi) lies from
/// the paper's fit, whether its area goes both below and above S0, and how many of its droplets
/// diverge or get stuck.

#include <functional>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {

/// The paper's fit of the mean tortuosity, f(phi) = a - c phi^b with a = 1.58, b = 3.87, c = 0.58.
double paper_tortuosity(double phi);

/// What every setting of a calibration runs.
struct CalibrationOptions {
  /// The sweep: porosities, media, droplets, seed, media options and exit conditions. Its
  /// droplet is replaced by each setting's, and its media are always MediaStream::calibration's. Default: 6 porosities
  /// x 10 media x 20 droplets.
  SweepOptions sweep = default_sweep();
  /// Area traces: `trace_media` non-overlapping media of porosity `trace_porosity` (the sweep's
  /// box, radii and gap), `trace_droplets` droplets each from random starts.
  double trace_porosity = 0.79;
  int trace_media = 2;
  int trace_droplets = 5;
  /// The resting test's scale S (see resting_travel): 1 for droplets of the default's size; S for
  /// a droplet whose lengths are S times the default's, with g fixed.
  double rest_scale = 1;

  static SweepOptions default_sweep();
  bool IsValid(std::string* why) const;
};

/// One porosity of a setting's sweep, beside the paper's value.
struct CalibrationPoint {
  double target_porosity = 0, porosity = 0;  ///< target, and mean exact porosity of its media
  int droplets = 0, passed = 0, stuck = 0, diverged = 0;
  double mean_t = 0, standard_error = 0;  ///< over passed droplets (0 if none; se 0 if < 2)
  /// Media with a passed droplet, and mean_t's standard error with them as clusters (0 if < 2),
  /// as SweepPoint's.
  int media_passed = 0;
  double media_standard_error = 0;
  double paper_t = 0;  ///< paper_tortuosity(porosity)
  /// |mean_t - paper_t| <= max(0.03, 2 media_standard_error), with at least two droplets passed:
  /// the media's error, since droplets in one medium share its throats.
  bool within = false;
};

/// A setting's figures and score (lower is better).
struct CalibrationResult {
  std::vector<CalibrationPoint> points;
  /// Root mean square of mean_t - paper_t over the porosities; a porosity where fewer than two
  /// droplets passed counts as paper_t - 1 (nothing measured: as far as a straight path).
  double rms_distance = 0;
  /// The same over the porosities where at least two droplets passed (0 if none), and their count:
  /// how well the curve's shape matches where it was measured.
  double measured_rms = 0;
  int measured = 0;
  int within = 0;                ///< porosities within the target
  double stuck_fraction = 0;     ///< over all sweep droplets
  double diverged_fraction = 0;  ///< over all sweep and trace droplets
  /// S / S0 inside the medium over the trace droplets that entered it (NaN: none entered).
  double area_min = 0, area_max = 0;
  bool area_both_sides = false;  ///< area_min < 0.95 and area_max > 1.02
  int trace_runs = 0, trace_passed = 0, trace_diverged = 0;
  /// Path length per time unit that the centre of a droplet resting on a floor of touching grains
  /// still travels once settled (NaN if it diverged there). A droplet that never comes to rest
  /// (its ring buzzing against the contacts) lengthens the path of every droplet that pauses in
  /// a pore, and so inflates T.
  double resting_travel = 0;
  bool comes_to_rest = false;  ///< resting_travel <= resting_limit(rest_scale)
  double steps = 0;            ///< steps taken by all sweep droplets
  /// rms_distance + diverged_fraction + (1 unless it comes to rest) + 0.05 (area not on both
  /// sides) + 0.05 stuck_fraction: the distance from the paper first, a diverging droplet as bad as
  /// a wrong T, a droplet that never rests ruled out, the rest tie-breaks.
  double score = 0;
};

/// Runs one setting: the sweep and the traces, with `threads` threads (0: all cores).
/// Deterministic whatever the thread count. `progress(done, total)` counts droplets.
/// Throws std::invalid_argument if the options or the droplet are invalid.
CalibrationResult run_calibration(const CalibrationOptions& options, const DropletParams& droplet, int threads,
                                  const std::function<void(long, long)>& progress = {});

/// The resting test of CalibrationResult::resting_travel on its own: the droplet is dropped on a
/// row of touching grains (radius 12, centres 20 apart, in a 200-wide periodic box), left 0.4 time
/// units to settle, then followed for 1 time unit. At scale S every length of the floor is S
/// times as long and every time sqrt(S) times (with g fixed, a model scaled in length by S runs
/// sqrt(S) times slower), so a droplet scaled with its floor is tested as the default one is.
double resting_travel(const DropletParams& droplet, double scale = 1);
/// The most a droplet resting at scale S may still travel a time unit: 0.01 sqrt(S) (speeds grow as
/// sqrt(S)).
double resting_limit(double scale);

/// One axis of a scan: a droplet parameter, by its option name, and its values.
struct ScanAxis {
  std::string name;
  std::vector<double> values;
};

/// The option names a scan can vary: every numeric field of visit_droplet_fields (all but
/// constraint-order and viscosity-step), in its order: masses, mass, radius, nrt, ks, kd, kc, cc,
/// gravity, dt, max-strain, constraint-iterations, max-depth, viscosity, viscosity-dilation.
std::vector<std::string> scan_parameter_names();
/// The same names as one line, "masses, mass, ...", for help texts and messages.
std::string scan_parameter_list();

/// Parses "name=v1,v2,..." or "name=lo:hi:n" (n values, evenly spaced) or "name=lo:hi:n:log"
/// (geometric). Throws std::invalid_argument with one line naming the axis for an unknown name,
/// an empty list, a non-finite value, lo > hi, n < 2, a log range not above 0, or a whole-number
/// parameter (masses, constraint-iterations) given a fraction.
ScanAxis parse_scan_axis(const std::string& text);

/// Sets the parameter `name` (one of scan_parameter_names) of `params`.
void set_scan_parameter(DropletParams& params, const std::string& name, double value);

/// `base` with the assignments of `text`, "name=value name=value ..." (names as for scan axes;
/// one value each), or `base` itself for "defaults". Throws std::invalid_argument naming the
/// setting for a bad assignment.
DropletParams apply_setting(const DropletParams& base, const std::string& text);

/// Every combination of the axes' values over `base`, the first axis varying slowest.
std::vector<DropletParams> scan_settings(const DropletParams& base, const std::vector<ScanAxis>& axes);
/// The labels of scan_settings' settings, in the same order: "name=value ..." over the axes
/// ("defaults" without axes).
std::vector<std::string> scan_labels(const std::vector<ScanAxis>& axes);

}  // namespace softdrop
