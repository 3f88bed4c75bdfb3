#include "cli/calibrate_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <type_traits>

#include "cli/columns.hpp"
#include "cli/output.hpp"
#include "service/calibration_service.hpp"
#include "softdrop/render.hpp"

namespace softdrop::cli {

CLI::App* add_calibrate_command(CLI::App& app, CalibrateArgs& a) {
  CLI::App* c = app.add_subcommand(
      "calibrate", "Scan droplet parameters against the paper: a small sweep and area traces per setting, ranked");
  c->fallthrough();
  c->footer(
      "Figures. score (lower is better) = rms_distance + diverged_fraction + 1 unless the droplet comes to rest + "
      "0.05 unless its area goes both below 0.95 and above 1.02 of S0 + 0.05 stuck_fraction. rms_distance = rms of "
      "<T> - f(phi) over the porosities (f(phi) - 1 where fewer than two droplets passed); measured_rms the same "
      "over the porosities where they did. within = porosities where |<T> - f(phi)| <= max(0.03, 2 "
      "media_standard_error), the error that takes each medium's droplets as one cluster.");
  auto* g = c->add_option_group("Calibration", "what every setting runs, and the grid");
  g->add_option("--scan", a.scans,
                "An axis of the grid, name=v1,v2,... or name=lo:hi:n or name=lo:hi:n:log (repeat for more axes; "
                "names: " +
                    scan_parameter_list() + "); the other parameters come from the Droplet options")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  g->add_option("--setting", a.settings,
                "Or one setting to run, \"[label:] name=value name=value ...\" over the Droplet options, or "
                "\"label:\" for those options as given (repeat for more; not with --scan)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  auto& s = a.calibration.sweep;
  g->add_option("--porosities", s.porosities, "Target porosities of each setting's sweep (media of --kind)")
      ->delimiter(',')
      ->capture_default_str();
  g->add_option("--media", s.media, "Media per porosity")->capture_default_str();
  g->add_option("--droplets", s.droplets, "Droplets per medium, from random starts")->capture_default_str();
  g->add_option("--seed", s.seed, "Seed of media and start positions (the same for every setting)")
      ->capture_default_str()
      ->check(seed_check());
  g->add_option("--trace-porosity", a.calibration.trace_porosity, "Porosity of the area traces' non-overlapping media")
      ->capture_default_str();
  g->add_option("--trace-media", a.calibration.trace_media, "Media of the area traces")->capture_default_str();
  g->add_option("--trace-droplets", a.calibration.trace_droplets, "Area-traced droplets per trace medium")
      ->capture_default_str();
  g->add_option("--rest-scale", a.calibration.rest_scale,
                "Resting test at S times the lengths (times sqrt(S) the times) of the default droplet's, for droplets "
                "scaled up with their grains")
      ->capture_default_str();
  g->add_flag("--skip-unstable", a.skip_unstable,
              "Record settings the limits refuse (unstable at their dt) as refused rows instead of refusing the scan");
  g->add_option("--threads", a.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  g->add_flag("--quiet", a.quiet, "No progress on stderr");
  auto* o = c->add_option_group("Output");
  o->add_option("--format", a.format, "The ranking on stdout: table, csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  o->add_option("--csv", a.csv, "One row per setting (parameters, figures, score), rewritten as each setting ends");
  o->add_option("--points", a.points, "One row per setting and porosity: <T>, its error, the paper's f(phi), stuck");
  o->add_option("--plot", a.plot, "The best settings' <T>(phi) against the paper's curve (.png, .svg, .pdf)");
  o->add_option("--best", a.best, "Settings drawn in the plot")->capture_default_str();
  auto* medium = add_medium_options(c, a.medium, false);
  medium->get_option("--medium")->description("(not used by calibrate)");
  medium->get_option("--porosity")->description("(not used by calibrate: see --porosities)");
  medium->get_option("--kind")->description("Media of each setting's sweep (the area traces' are non-overlapping)");
  auto* d = add_droplet_options(c, s.droplet);
  add_exit_options(d, s.run);
  return c;
}

std::vector<DropletParams> check_calibrate(CalibrateArgs& a, std::vector<std::string>* labels) {
  if (!a.medium.file.empty())
    throw std::invalid_argument("medium: calibrate generates its media; --medium is not used");
  resolve_medium(a.medium);
  a.calibration.sweep.medium = a.medium.options;
  std::string why;
  if (!a.calibration.IsValid(&why)) throw std::invalid_argument(why);
  check_threads(a.threads);
  if (a.best < 1 || a.best > 20)
    throw std::invalid_argument("best = " + std::to_string(a.best) + ": must be in [1, 20]");
  if (!a.csv.empty()) check_output_path("--csv", a.csv);
  if (!a.points.empty()) check_output_path("--points", a.points);
  if (!a.plot.empty()) check_picture_path("--plot", a.plot);
  std::vector<ScanAxis> axes;
  double count = 1;
  for (const std::string& text : a.scans) {
    axes.push_back(parse_scan_axis(text));
    for (const ScanAxis& earlier : std::vector<ScanAxis>(axes.begin(), axes.end() - 1))
      if (earlier.name == axes.back().name)
        throw std::invalid_argument("scan '" + text + "': " + earlier.name + " scanned twice");
    count *= static_cast<double>(axes.back().values.size());
  }
  if (count > 10000) throw std::invalid_argument("scan: " + fmt(count, 6) + " settings; at most 10 000");
  if (!a.settings.empty() && !a.scans.empty()) throw std::invalid_argument("setting: --setting and --scan do not mix");
  std::vector<DropletParams> settings;
  std::vector<std::string> names;  // "name: assignments" names a setting; otherwise its text does
  for (const std::string& text : a.settings) {
    const std::size_t colon = text.find(':');
    const bool named = colon != std::string::npos && text.find('=') > colon;
    const std::string assignments = named ? text.substr(colon + 1) : text;
    names.push_back(named ? text.substr(0, colon) : text);
    // "name:" alone is the Droplet options as given, under that name.
    const bool as_given = named && assignments.find_first_not_of(" \t") == std::string::npos;
    if (as_given && names.back().find_first_not_of(" \t") == std::string::npos)
      throw std::invalid_argument("setting '" + text + "': an empty name and no assignments");
    settings.push_back(as_given ? a.calibration.sweep.droplet
                                : apply_setting(a.calibration.sweep.droplet, assignments));
  }
  if (a.settings.empty()) settings = scan_settings(a.calibration.sweep.droplet, axes);
  if (labels) *labels = a.settings.empty() ? scan_labels(axes) : names;
  if (!a.skip_unstable)
    for (std::size_t i = 0; i < settings.size(); ++i)
      if (!settings[i].IsValid(&why))
        throw std::invalid_argument("setting " + std::to_string(i) + ": " + why +
                                    " (--skip-unstable records it instead)");
  return settings;
}

namespace {

using Row = CalibrationRow;

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

Table settings_table(const std::vector<const Row*>& rows) {
  Table t;
  t.header = {"setting", "status"};
  const DropletParams names_only;
  visit_droplet_fields([&](const DropletField& field, const auto&) { t.header.push_back(column_name(field.key)); },
                       names_only);
  t.header.insert(t.header.end(),
                  {"score", "rms_distance", "measured_rms", "measured", "within", "stuck_fraction", "diverged_fraction",
                   "area_min", "area_max", "area_both_sides", "trace_passed", "trace_runs", "resting_travel",
                   "comes_to_rest", "steps_per_second", "seconds", "label"});
  for (const Row* r : rows) {
    const DropletParams& d = r->droplet;
    const CalibrationResult& c = r->result;
    const bool ok = r->refused.empty();
    auto fig = [&](double v) { return ok ? number_or_null(v) : nlohmann::json(nullptr); };
    std::vector<nlohmann::json> row{r->setting, ok ? "ok" : "refused: " + r->refused};
    visit_droplet_fields(
        [&](const DropletField&, const auto& value) {
          if constexpr (std::is_arithmetic_v<std::decay_t<decltype(value)>>)
            row.emplace_back(value);
          else
            row.emplace_back(to_string(value));
        },
        d);
    row.insert(row.end(),
               {fig(c.score), fig(c.rms_distance), fig(c.measured_rms), ok ? nlohmann::json(c.measured) : nullptr,
                ok ? nlohmann::json(c.within) : nullptr, fig(c.stuck_fraction), fig(c.diverged_fraction),
                fig(c.area_min), fig(c.area_max), ok ? nlohmann::json(c.area_both_sides) : nullptr,
                ok ? nlohmann::json(c.trace_passed) : nullptr, ok ? nlohmann::json(c.trace_runs) : nullptr,
                fig(c.resting_travel), ok ? nlohmann::json(c.comes_to_rest) : nullptr,
                fig(r->seconds > 0 ? c.steps / r->seconds : NAN), fig(r->seconds), r->label});
    t.rows.push_back(std::move(row));
  }
  return t;
}

Table points_table(const std::vector<const Row*>& rows) {
  Table t;
  t.header = {"setting",
              "target_porosity",
              "porosity",
              "droplets",
              "passed",
              "stuck",
              "diverged",
              "mean_tortuosity",
              "standard_error",
              "media_passed",
              "media_standard_error",
              "paper_tortuosity",
              "within"};
  for (const Row* r : rows)
    for (const CalibrationPoint& p : r->result.points)
      t.rows.push_back({r->setting, p.target_porosity, p.porosity, p.droplets, p.passed, p.stuck, p.diverged,
                        p.passed > 0 ? nlohmann::json(p.mean_t) : nullptr,
                        p.passed > 1 ? nlohmann::json(p.standard_error) : nullptr, p.media_passed,
                        p.media_passed > 1 ? nlohmann::json(p.media_standard_error) : nullptr, p.paper_t, p.within});
  return t;
}

// The best settings' points with error bars over the paper's curve.
void plot_best(const std::vector<const Row*>& ranked, int best, const std::string& path) {
  Chart c;
  Series paper;
  for (int i = 0; i <= 100; ++i) {
    const double phi = 0.45 + 0.55 * i / 100.0;
    paper.x.push_back(phi), paper.y.push_back(paper_tortuosity(phi));
  }
  paper.label = "paper: 1.58 − 0.58 φ^3.87";
  paper.colour = {0.1, 0.1, 0.1, 1};
  c.series.push_back(paper);
  const Rgba colours[] = {
      {0.8, 0.1, 0.1, 1}, {0.1, 0.35, 0.8, 1}, {0.1, 0.6, 0.2, 1}, {0.7, 0.4, 0.0, 1}, {0.5, 0.1, 0.6, 1}};
  int drawn = 0;
  for (const Row* r : ranked) {
    if (drawn == best) break;
    if (!r->refused.empty()) continue;
    Series s;
    s.style = Series::Style::points;
    s.width = 4;
    s.colour = colours[drawn % 5];
    for (const CalibrationPoint& p : r->result.points)
      if (p.passed >= 2) s.x.push_back(p.porosity), s.y.push_back(p.mean_t), s.err.push_back(p.media_standard_error);
    s.label = r->label + " (score " + fmt(r->result.score, 3) + ")";
    if (!s.x.empty()) c.series.push_back(std::move(s)), ++drawn;
  }
  c.x_label = "porosity φ";
  c.y_label = "mean tortuosity ⟨T⟩";
  c.title = "calibration: the best settings against the paper";
  render_chart(c, RenderStyle{}, path);
}

}  // namespace

namespace {
// The program's observer of a scan: the progress line with its ETA (this setting's pace for its
// rest, the mean setting's time for the settings after it), each setting's figures, the tables
// rewritten after each, and Ctrl-C.
class CalibrationLines : public CalibrationObserver {
 public:
  CalibrationLines(const CalibrateArgs& a, std::size_t settings)
      : a_(a),
        settings_(settings),
        stop_("\nsoftdrop: finishing the setting in flight (Ctrl-C again to leave now)\n") {}
  void progress(int setting, long done, long total, double seconds) override {
    const auto now = std::chrono::steady_clock::now();
    if (setting != setting_) setting_ = setting, setting_began_ = seconds, s0_ = now, last_ = now;
    if (a_.quiet || (done != total && now - last_ < std::chrono::seconds(tty_ ? 1 : 30))) return;
    last_ = now;
    const double spent = std::chrono::duration<double>(now - s0_).count();
    const double rest = spent / static_cast<double>(done) * static_cast<double>(total - done);
    const auto i = static_cast<std::size_t>(setting);
    const double per_setting = i > 0 ? setting_began_ / static_cast<double>(i) : spent + rest;
    const double eta = rest + per_setting * static_cast<double>(settings_ - i - 1);
    std::cerr << (tty_ ? "\r" : "") << "calibrate: setting " << i << " (" << i + 1 << " of " << settings_
              << "), droplets " << done << "/" << total << ", ETA " << fmt(eta, 3) << " s" << (tty_ ? "\033[K" : "\n")
              << std::flush;
  }
  bool finished(const std::vector<CalibrationRow>& rows) override {
    const CalibrationRow& row = rows.back();
    if (!a_.quiet && row.refused.empty()) {
      const CalibrationResult& r = row.result;
      std::cerr << (tty_ ? "\r" : "") << "calibrate: setting " << row.setting << ": score " << fmt(r.score, 4)
                << ", rms " << fmt(r.rms_distance, 4) << " (measured " << fmt(r.measured_rms, 4) << ")"
                << ", stuck " << fmt(r.stuck_fraction, 3) << ", diverged " << fmt(r.diverged_fraction, 3)
                << (std::isnan(r.area_min) ? std::string(", no area trace")
                                           : ", S/S0 in [" + fmt(r.area_min, 4) + ", " + fmt(r.area_max, 4) + "]")
                << ", at rest "
                << (r.comes_to_rest ? "yes" : "no (travels " + fmt(r.resting_travel, 3) + " a time unit)")
                << (tty_ ? "\033[K\n" : "\n");
    }
    std::vector<const Row*> in_order;
    for (const Row& r : rows) in_order.push_back(&r);
    if (!a_.csv.empty()) settings_table(in_order).write_csv(a_.csv);
    if (!a_.points.empty()) points_table(in_order).write_csv(a_.points);
    return true;
  }
  bool stop_requested() override { return stop_.requested(); }
  int exit_code() const { return stop_.exit_code(); }

 private:
  const CalibrateArgs& a_;
  std::size_t settings_;
  StopOnSignal stop_;
  const bool tty_ = ::isatty(2) != 0;
  int setting_ = -1;
  double setting_began_ = 0;  // seconds since the scan began, at the setting's first droplet
  std::chrono::steady_clock::time_point s0_, last_;
};
}  // namespace

int run_calibrate(CalibrateArgs& a) {
  CalibrationScan scan;
  scan.settings = check_calibrate(a, &scan.labels);
  scan.calibration = a.calibration;
  scan.threads = a.threads;
  const auto t0 = std::chrono::steady_clock::now();
  CalibrationLines lines(a, scan.settings.size());
  const std::vector<CalibrationRow> rows = run_calibration_scan(scan, lines);
  std::vector<const Row*> best;
  for (const Row& r : rows) best.push_back(&r);
  if (!a.plot.empty() && std::any_of(rows.begin(), rows.end(), [](const Row& r) { return r.refused.empty(); }))
    plot_best(best, a.best, a.plot);
  settings_table(best).print(std::cout, a.format);
  if (!a.quiet)
    std::cerr << "calibrate: " << rows.size() << " of " << scan.settings.size() << " settings in "
              << fmt(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 4) << " s\n";
  return lines.exit_code();
}

}  // namespace softdrop::cli
