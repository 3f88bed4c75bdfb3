// `softdrop fit` and `softdrop averagings`: the paper's analyses of a sweep's points.
#include "cli/fit_command.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "cli/common_options.hpp"
#include "cli/output.hpp"
#include "cli/sweep_report_command.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/render.hpp"
#include "softdrop/store.hpp"
#include "softdrop/version.hpp"
#include "studies/averaging.hpp"
#include "studies/calibration.hpp"
#include "studies/fit.hpp"

namespace softdrop::cli {
namespace {
// Below this many media with a passed droplet, a porosity's media error is itself too uncertain
// to weigh a fit without a warning (the spread of a standard deviation from G clusters is about
// 1 / sqrt(2 (G - 1)) of it: 24 % at 10).
constexpr int kFewMedia = 10;

RenderStyle plot_style(int size, double dpi) {
  RenderStyle style;
  style.width = size;
  style.dpi = dpi;
  std::string why;
  if (!style.IsValid(&why)) throw std::invalid_argument(why);
  return style;
}
}  // namespace

int run_fit(const FitArgs& a) {
  if (!a.plot.empty()) check_picture_path("--plot", a.plot), plot_style(a.size, a.dpi);
  if (!a.json_file.empty()) check_output_path("--json", a.json_file);
  const FitErrors errors = a.errors == "droplets" ? FitErrors::droplets : FitErrors::media;
  const FitAveraging averaging = a.mean == "per-medium" ? FitAveraging::per_medium : FitAveraging::pooled;
  if (averaging == FitAveraging::per_medium && errors == FitErrors::droplets)
    throw std::invalid_argument(
        "--errors droplets: a per-medium mean has only its error over the media "
        "(leave --errors out, or fit --mean pooled)");
  std::vector<FitPoint> points;
  bool used_errors = true;  // false: a porosity,tortuosity,standard_error file, which brings its own
  if (!a.points.empty()) {
    std::ifstream in(a.points);
    if (!in) throw std::runtime_error("--points '" + a.points + "': cannot read");
    points = read_fit_points(in, a.points, errors, &used_errors, averaging);
  } else {
    auto store = open_sweep_store(a.db, OpenMode::read_only);
    int few = 0, fewest = kFewMedia;
    for (const SweepPoint& p : sweep_points(store->media(pick_sweep(*store, a.sweep, a.db)))) {
      const bool per_medium = averaging == FitAveraging::per_medium;
      const double se = per_medium                   ? p.per_medium_standard_error
                        : errors == FitErrors::media ? p.media_standard_error
                                                     : p.standard_error;
      if (p.passed < 2 || !(se > 0)) continue;
      points.push_back({p.porosity, per_medium ? p.per_medium_t : p.mean_t, se});
      if (p.media_passed < kFewMedia) ++few, fewest = std::min(fewest, p.media_passed);
    }
    if (errors == FitErrors::media && few > 0)
      std::cerr << "fit: warning: " << few << " of " << points.size() << " points have their error from fewer than "
                << kFewMedia << " media with a passed droplet (" << fewest << " at the least), too few for the "
                << "error itself to be sure (sweep more media, or weigh by --errors droplets)\n";
  }
  const auto fit = [&](FitLaw law) {
    try {
      return fit_law(law, points);
    } catch (const std::invalid_argument& e) {  // too few points: say where they came from
      throw std::invalid_argument((a.points.empty() ? "--db '" + a.db + "': " : "--points '" + a.points + "': ") +
                                  e.what());
    }
  };
  const FitResult power = fit(FitLaw::power), log = fit(FitLaw::log);
  for (const FitResult* r : {&power, &log})
    if (!r->warning.empty()) std::cerr << "fit: warning: " << r->warning << '\n';
  for (const FitResult* r : {&power, &log})
    if (r->dof <= 0)
      std::cerr << "fit: warning: " << to_string(r->law) << " law: " << points.size() << " points for "
                << r->values.size() << " parameters leave 0 degrees of freedom; its errors and the AIC "
                << "comparison mean nothing (sweep more porosities)\n";

  nlohmann::ordered_json j;
  j["version"] = kVersion;
  j["points"] = points.size();
  if (used_errors) j["errors"] = a.errors, j["mean"] = a.mean;
  for (const FitResult* r : {&power, &log}) {
    nlohmann::ordered_json f;
    f["law"] = r->law == FitLaw::power ? "T = a - c phi^b" : "T = 1 - p ln(phi)";
    for (std::size_t i = 0; i < r->names.size(); ++i)
      f[r->names[i]] = {{"value", r->values[i]}, {"error", r->errors[i]}};
    f["chi2"] = r->chi2;
    f["dof"] = r->dof;
    f["reduced_chi2"] = r->reduced_chi2;
    f["aic"] = r->aic;
    f["residuals"] = r->residuals;
    f["message"] = r->message;
    if (!r->warning.empty()) f["warning"] = r->warning;
    j[to_string(r->law)] = f;
  }
  // The paper's own f(phi) against these points: nothing fitted, so its chi2 has one degree of
  // freedom a point (on media no calibration saw, the out-of-sample test of the model).
  std::vector<double> paper_residuals;
  double paper_chi2 = 0;
  for (const FitPoint& p : points) {
    paper_residuals.push_back((p.t - paper_tortuosity(p.phi)) / p.se);
    paper_chi2 += paper_residuals.back() * paper_residuals.back();
  }
  j["paper"] = {{"law", "T = 1.58 - 0.58 phi^3.87"},
                {"chi2", paper_chi2},
                {"dof", points.size()},
                {"residuals", paper_residuals}};
  j["delta_aic_log_minus_power"] = log.aic - power.aic;
  j["preferred"] = power.dof <= 0 || log.dof <= 0 ? nlohmann::ordered_json(nullptr)
                                                  : nlohmann::ordered_json(log.aic > power.aic ? "power" : "log");
  if (!a.json_file.empty()) write_file_atomically(a.json_file, j.dump(2) + "\n");
  if (a.format == "json") {
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << points.size() << " points";
    if (used_errors)
      std::cout << (averaging == FitAveraging::per_medium ? " (each medium's <T> first, then over media)" : "")
                << " weighed by the " << (errors == FitErrors::media ? "media's" : "droplets'") << " standard errors";
    std::cout << "\n";
    for (const FitResult* r : {&power, &log}) {
      std::cout << (r->law == FitLaw::power ? "T = a - c phi^b  " : "T = 1 - p ln phi ");
      for (std::size_t i = 0; i < r->names.size(); ++i)
        std::cout << "  " << r->names[i] << " = " << fmt(r->values[i], 5) << " +- " << fmt(r->errors[i], 2);
      std::cout << "   chi2 = " << fmt(r->chi2, 5) << " (dof " << r->dof << ", reduced " << fmt(r->reduced_chi2, 4)
                << "), AIC = " << fmt(r->aic, 5) << "\n";
    }
    std::cout << "paper's f          1.58 - 0.58 phi^3.87, nothing fitted:  chi2 = " << fmt(paper_chi2, 5) << " (dof "
              << points.size() << ")\n";
    std::cout << "AIC(log) - AIC(power) = " << fmt(log.aic - power.aic, 4);
    if (power.dof <= 0 || log.dof <= 0)
      std::cout << " (no verdict: a fit with 0 degrees of freedom passes through every point)\n";
    else
      std::cout << (log.aic > power.aic ? " (the power law is preferred)\n" : " (the log law is preferred)\n");
    std::cout << "phi         T          se         resid_power  resid_log  resid_paper\n";
    for (std::size_t i = 0; i < points.size(); ++i) {
      std::ostringstream row;
      row << std::left << std::setw(12) << fmt(points[i].phi, 6) << std::setw(11) << fmt(points[i].t, 6)
          << std::setw(11) << fmt(points[i].se, 3) << std::setw(13) << fmt(power.residuals[i], 3) << std::setw(11)
          << fmt(log.residuals[i], 3) << fmt(paper_residuals[i], 3);
      std::cout << row.str() << "\n";
    }
  }
  if (!a.plot.empty()) {
    Chart c;
    Series data;
    data.style = Series::Style::points;
    data.width = 3.5;
    data.colour = Rgba{0.1, 0.1, 0.1, 1};
    data.label = "⟨T⟩ ± standard error";
    for (const FitPoint& p : points) data.x.push_back(p.phi), data.y.push_back(p.t), data.err.push_back(p.se);
    double lo = 1, hi = 0;
    for (const FitPoint& p : points) lo = std::min(lo, p.phi), hi = std::max(hi, p.phi);
    auto curve = [&](auto&& f, Rgba colour, const std::string& label) {  // f(phi) over the points' range
      Series s;
      s.colour = colour;
      s.label = label;
      for (int i = 0; i <= 100; ++i) {
        const double phi = lo + (hi - lo) * i / 100.0;
        s.x.push_back(phi);
        s.y.push_back(f(phi));
      }
      return s;
    };
    auto law = [](const FitResult& r) { return [&r](double phi) { return fit_law_value(r.law, r.values, phi); }; };
    auto value = [](const FitResult& r, std::size_t i) {
      return r.names[i] + " = " + with_error(r.values[i], r.errors[i]);
    };
    // The paper's fit beside ours, over the same range.
    c.series = {curve(paper_tortuosity, Rgba{0.55, 0.55, 0.55, 1}, "paper: 1.58 − 0.58 φ^3.87"),
                curve(law(power), Rgba{0.8, 0.1, 0.1, 1},
                      "a − c φᵇ: " + value(power, 0) + ", " + value(power, 1) + ", " + value(power, 2)),
                curve(law(log), Rgba{0.1, 0.3, 0.8, 1}, "1 − p ln φ: " + value(log, 0)), data};
    c.x_label = "porosity φ";
    c.y_label = "tortuosity ⟨T⟩";
    render_chart(c, plot_style(a.size, a.dpi), a.plot);
  }
  return 0;
}

namespace {
// The paper averages 2 000 media in groups of 100 (20 groups); a smaller store gets the same
// number of groups where it can, and at least 2 media a group so that a group averages something.
int default_group(std::size_t media) {
  const auto n = static_cast<int>(std::min<std::size_t>(media, 1'000'000));
  return std::clamp(n / 20, std::min(2, std::max(n, 1)), 100);
}
}  // namespace

int run_averagings(const AveragingArgs& args) {
  AveragingArgs a = args;
  if (a.group < 0) throw std::invalid_argument("group = " + std::to_string(a.group) + ": must be >= 1");
  if (!a.plot.empty()) check_picture_path("--plot", a.plot), plot_style(a.size, a.dpi);
  if (!a.csv.empty()) check_output_path("--csv", a.csv);
  auto store = open_sweep_store(a.db, OpenMode::read_only);
  std::vector<MediumPoint> points;
  for (const SweepMedium& m : store->media(pick_sweep(*store, a.sweep, a.db)))
    if (m.passed > 0) points.push_back({m.porosity, m.mean_t});
  if (points.empty()) throw std::invalid_argument(a.db + ": no medium with a passed droplet to average");
  if (a.group == 0) {
    a.group = default_group(points.size());
    std::cerr << "averagings: groups of " << a.group << " (from the " << points.size()
              << " media with a passed droplet; --group sets it)\n";
  }
  if (points.size() < static_cast<std::size_t>(a.group))
    throw std::invalid_argument("group = " + std::to_string(a.group) + ": larger than the " +
                                std::to_string(points.size()) + " media with a passed droplet (use --group " +
                                std::to_string(default_group(points.size())) + ")");
  const Leftover leftover = a.leftover == "keep" ? Leftover::keep : Leftover::drop;
  const std::size_t left = points.size() % static_cast<std::size_t>(a.group);
  if (left > 0 && leftover == Leftover::drop)
    std::cerr << "averagings: " << left << " of the " << points.size() << " media do not fill a group of " << a.group
              << " and are left out: the highest in T (type 1) and in phi (type 2); --leftover "
                 "keep averages them\n";
  const auto by_t = group_averages(points, AveragingType::by_t, a.group, leftover);
  const auto by_phi = group_averages(points, AveragingType::by_phi, a.group, leftover);
  Table t;
  t.header = {"averaging", "porosity", "mean_tortuosity", "porosity_standard_error", "standard_error", "count"};
  for (const auto& [type, groups] : {std::pair{1, &by_t}, std::pair{2, &by_phi}})
    for (const GroupAverage& g : *groups) t.rows.push_back({type, g.phi, g.t, g.phi_se, g.t_se, g.count});
  t.print(std::cout, "table");
  if (!a.csv.empty()) t.write_csv(a.csv);
  if (!a.plot.empty()) {
    Chart c;
    Series cloud;
    cloud.style = Series::Style::points;
    cloud.width = 3.2;  // the per-medium points, seen behind the averages
    cloud.colour = Rgba{0.35, 0.35, 0.35, 0.75};
    cloud.label = "media (" + std::to_string(points.size()) + ")";
    for (const MediumPoint& p : points) cloud.x.push_back(p.phi), cloud.y.push_back(p.t);
    auto series = [](const std::vector<GroupAverage>& groups, Rgba colour, const std::string& label) {
      Series s;
      s.colour = colour;
      s.label = label;
      s.width = 2.5;
      for (const GroupAverage& g : groups) s.x.push_back(g.phi), s.y.push_back(g.t), s.err.push_back(g.t_se);
      return s;
    };
    c.series = {cloud, series(by_t, Rgba{0.8, 0.1, 0.1, 1}, "type 1: sorted by T"),
                series(by_phi, Rgba{0.1, 0.3, 0.8, 1}, "type 2: sorted by φ")};
    c.x_label = "porosity φ";
    c.y_label = "tortuosity ⟨T⟩";
    c.title = "groups of " + std::to_string(a.group) + " media";
    if (left > 0 && leftover == Leftover::keep) c.title += ", the last of " + std::to_string(left);
    render_chart(c, plot_style(a.size, a.dpi), a.plot);
  }
  return 0;
}

void add_fit_commands(CLI::App& app, FitArgs& f, AveragingArgs& v) {
  CLI::App* ft =
      app.add_subcommand("fit", "Weighted least-squares fits of <T>(phi): a - c phi^b and 1 - p ln phi (NLopt)");
  ft->fallthrough();
  auto* src = ft->add_option_group("Data");
  src->add_option("--db", f.db, "Sweep store: fit its per-porosity points");
  src->add_option(
         "--points", f.points,
         "Or a CSV file with columns porosity,tortuosity,standard_error (or the output of sweep-report --format csv)")
      ->check(CLI::ExistingFile);
  src->require_option(1);
  ft->add_option("--sweep", f.sweep, "Sweep id (default: the only one)")->check(id_check());
  ft->add_option("--errors", f.errors,
                 "Weights of a sweep's points: the standard error of each porosity's <T> with its media as "
                 "clusters (media), or with every droplet taken as independent (droplets: smaller, as droplets "
                 "of one medium share its dead ends); a porosity,tortuosity,standard_error file brings its own")
      ->capture_default_str()
      ->check(CLI::IsMember({"media", "droplets"}));
  ft->add_option("--mean", f.mean,
                 "Which <T> of a sweep's porosity: pooled over its passed droplets (a medium counts by the "
                 "droplets that passed it), or per-medium: each medium's <T> first, then their mean over the "
                 "media, weighed by its error over the media")
      ->capture_default_str()
      ->check(CLI::IsMember({"pooled", "per-medium"}));
  ft->add_option("--plot", f.plot, "Also draw T(phi) with error bars and both fits (.png, .svg, .pdf)");
  ft->add_option("--size", f.size, "Plot width in points (1/72 inch)")->capture_default_str();
  ft->add_option("--dpi", f.dpi, "PNG resolution of the plot: pixels an inch (300 for print)")->capture_default_str();
  ft->add_option("--json", f.json_file, "Also write the fits as JSON to this file");
  ft->add_option("--format", f.format, "table or json")->capture_default_str()->check(CLI::IsMember({"table", "json"}));

  CLI::App* av = app.add_subcommand("averagings", "The paper's two averagings of per-medium points (by T, by phi)");
  av->fallthrough();
  av->add_option("--db", v.db, "Sweep store")->capture_default_str();
  av->add_option("--sweep", v.sweep, "Sweep id (default: the only one)")->check(id_check());
  av->add_option("--group", v.group,
                 "Points per group (default: the paper's 100, or a twentieth of the media when the store has "
                 "fewer than 2000, at least 2)")
      ->check(positive_check());
  av->add_option("--leftover", v.leftover,
                 "Media left over after the last full group: drop (every group full, as the "
                 "paper's) or keep (averaged as a last, smaller group)")
      ->capture_default_str()
      ->check(CLI::IsMember({"drop", "keep"}));
  av->add_option(
      "--csv", v.csv,
      "Write the groups (averaging,porosity,mean_tortuosity,porosity_standard_error,standard_error,count) to this CSV");
  av->add_option("--plot", v.plot, "Draw the per-medium points and both averagings");
  av->add_option("--size", v.size, "Plot width in points (1/72 inch)")->capture_default_str();
  av->add_option("--dpi", v.dpi, "PNG resolution of the plot: pixels an inch (300 for print)")->capture_default_str();
}

}  // namespace softdrop::cli
