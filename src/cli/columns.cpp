#include "cli/columns.hpp"

#include <algorithm>
#include <iostream>
#include <map>
#include <stdexcept>

#include "cli/output.hpp"
#include "softdrop/droplet.hpp"

namespace softdrop::cli {
namespace {

// The rules: T is "tortuosity", qualified in front (mean_, best_, held_out_, geometric_ ...); a
// standard error is "standard_error", qualified in front when the row holds more than one
// (held_out_standard_error is held_out_tortuosity's); porosity is "porosity", never phi; time is
// "time", never t; ids are the thing's name (run, sweep), never id or run_id; a count of things is
// the plural (droplets, grains) or, for grains touched, "touched", and their indices
// "touched_grains".
const std::vector<ColumnName> kColumns = {
    {"a", "1", "fit: the power law's a in T = a - c porosity^b (an object of value and error)"},
    {"accepted", "1", "1 if the strategy kept this candidate (or, for a generation, one of its candidates)"},
    {"accepted_candidate", "index", "the candidate the generation kept (empty: none)"},
    {"aic", "1", "fit: Akaike information criterion of the law"},
    {"archipelago", "id", "the run id of the first island of this run's islands (empty: not islands)"},
    {"area", "length^2", "the droplet's area (shoelace over its ring)"},
    {"area_both_sides", "1", "calibrate: the area trace passed below and above S0 inside the medium"},
    {"area_max", "1", "calibrate: largest area_ratio inside the medium"},
    {"area_min", "1", "calibrate: smallest area_ratio inside the medium"},
    {"area_ratio", "1", "area / s0 (empty before the droplet reached the medium)"},
    {"at_dt", "", "held-out droplets at the run's time step (an object of the names here)"},
    {"at_half_dt", "", "the same starts at half the time step"},
    {"averaging", "1", "averagings: 1 = media grouped by their T, 2 = by their porosity"},
    {"b", "1", "fit: the power law's exponent b"},
    {"best_candidate_tortuosity", "1", "the best value among a generation's passing candidates"},
    {"best_generation", "index", "the generation whose arrangement holds best_tortuosity"},
    {"best_island", "index", "the island holding the best arrangement"},
    {"best_run", "id", "the run holding the best arrangement"},
    {"best_tortuosity", "1", "the value of the arrangement a search stands on after this generation"},
    {"buffer_rows", "1", "tortuosity: rows of open fluid above and below the image in the flow solve"},
    {"c", "1", "fit: the power law's c"},
    {"candidate", "index", "a candidate's number in its generation"},
    {"candidates", "1", "candidates in the generation"},
    {"change", "1", "tortuosity: relative change from the coarser to the finer image"},
    {"chi2", "1", "fit: sum of squared residuals over their errors"},
    {"clogged", "1", "simulate --second-droplet: pairs that ended with both droplets stuck"},
    {"comes_to_rest", "1", "calibrate: the droplet came to rest on a flat floor"},
    {"commit_seconds", "s", "sweep: wall time spent storing media"},
    {"concentration", "1", "tortuosity: the steady diffusion's concentration, 1 at the top, 0 at the bottom"},
    {"connected", "1", "top pore pixels with a pore path to the bottom"},
    {"contact_steps", "1", "--second-droplet: steps in which the two droplets' rings were in contact"},
    {"count", "1", "points in the group"},
    {"created", "UTC time", "when the record was first written"},
    {"db", "", "the database file"},
    {"delta_aic_log_minus_power", "1", "fit: aic of the log law minus that of the power law"},
    {"differs_in", "", "the options that set this sweep apart from the others in the file"},
    {"diffusive_tortuosity", "1",
     "phi D / D_eff from a steady diffusion through the pore image (PoreSpy's tortuosity_fd)"},
    {"distance", "length", "tortuosity: each pore pixel's shortest pore path to the bottom (inf: none)"},
    {"diverged", "1", "droplets whose run diverged (non-finite positions)"},
    {"diverged_fraction", "1", "diverged / droplets"},
    {"dof", "1", "fit: degrees of freedom"},
    {"done", "1", "a sweep's media stored"},
    {"droplet", "index", "a droplet's number in its run, medium or study"},
    {"droplet_tortuosity", "", "tortuosity: the droplets' mean T over random starts (an object of the names here)"},
    {"droplets", "1", "droplets pushed"},
    {"dropped_evaluations", "1", "speculation: evaluations computed and thrown away"},
    {"dropped_steps", "1", "speculation: time steps computed and thrown away"},
    {"droplets_this_session", "1", "sweep: droplets this invocation ran"},
    {"dt", "time", "the time step"},
    {"dt_shift", "1", "the mean of T(dt / 2) - T(dt) over the starts that passed at both"},
    {"dt_shift_error", "1", "dt_shift's standard error"},
    {"effective_diffusivity", "1", "D_eff / D of the pore image"},
    {"enter", "time", "when the droplet's lowest mass reached the top of the medium (NaN: never)"},
    {"error", "", "fit: a coefficient's standard error"},
    {"errors", "", "fit: the errors fitted with (media or droplets)"},
    {"evaluations", "1", "candidates evaluated (generation 0's included)"},
    {"evaluations_per_second", "1/s", "evaluations over wall time"},
    {"extrapolated", "1", "tortuosity: 2 x the finer value - the coarser (first-order convergence)"},
    {"finished", "UTC time", "when the generation was written"},
    {"first_held_at", "time",
     "sweep --second-droplet: when the pair's first droplet was first held while the second moved (since its own "
     "start; empty: never)"},
    {"format", "", "a grain file's format name"},
    {"formation_factor", "1", "D / D_eff of the pore image: diffusive_tortuosity / porosity"},
    {"freed", "1",
     "simulate --second-droplet: first droplets held (found stuck while the second moved) that then passed"},
    {"generation", "index", "a generation's number in its run (0: the starting arrangement)"},
    {"generations", "1", "the last generation stored"},
    {"generations_run", "1", "generations this invocation ran"},
    {"geometric_standard_error", "1", "geometric_tortuosity's standard error over its starts"},
    {"geometric_tortuosity", "1",
     "shortest pore path from the top to the bottom over the height, averaged over top pixels"},
    {"grain", "index", "a grain's index in its medium"},
    {"grains", "1", "grains in the medium"},
    {"half_dt", "1", "1 if the held-out value was also measured at dt / 2"},
    {"half_dt_mean_tortuosity", "1", "mean_tortuosity at dt / 2, over the same starts"},
    {"half_dt_passed", "1", "droplets that passed at dt / 2"},
    {"half_dt_standard_error", "1", "half_dt_mean_tortuosity's standard error"},
    {"height", "length", "the medium's height H"},
    {"held", "1", "simulate --second-droplet: first droplets held at a stuck or rest verdict while the second moved"},
    {"held_at", "time", "--second-droplet: when the droplet was first held (since its own start; empty: never)"},
    {"held_out", "", "the held-out value of the best arrangement (an object of the names here)"},
    {"held_out_standard_error", "1", "held_out_tortuosity's standard error"},
    {"held_out_starts", "1", "the random starts held_out_tortuosity is the mean over"},
    {"held_out_tortuosity", "1", "mean T over random starts the search never saw (softdrop validate)"},
    {"hydrodynamic_tortuosity", "1", "<|u|> / <-u_y> of creeping flow through the pore image (Matyka 2008)"},
    {"image_porosity", "1", "tortuosity: pore pixels / pixels, at each resolution"},
    {"in_contact", "1", "simulate --second-droplet: pairs whose rings came into contact"},
    {"in_search_tortuosity", "1", "the value the search gave the arrangement"},
    {"inside_max_area_ratio", "1", "largest area_ratio over every step inside the medium"},
    {"inside_min_area_ratio", "1", "smallest area_ratio over every step inside the medium"},
    {"island", "index", "this run's island among its islands (empty: not islands)"},
    {"islands", "", "one object per island"},
    {"kept_steps", "1", "speculation: time steps computed and kept"},
    {"kind", "", "the move that made a candidate: initial, all, single, relocate, migrate; a generation's, or mixed"},
    {"label", "", "calibrate: the setting's label"},
    {"lambda", "1", "candidates per generation"},
    {"lanes", "1", "speculation: SIMD lanes"},
    {"last_generation", "index", "the run's last stored generation"},
    {"law", "", "fit: the law's formula"},
    {"leave", "time", "when the droplet's highest mass left the bottom of the medium (NaN: never)"},
    {"log", "", "fit: the law T = 1 - p ln(porosity) fitted (an object of the names here)"},
    {"mass", "index", "a ring mass's index"},
    {"max_penetration", "length", "deepest overlap of a mass with a grain over the run"},
    {"mean", "", "fit: the mean fitted (pooled or per-medium); dt_shift: its value"},
    {"mean_tortuosity", "1", "<T>: mean T over the passed droplets"},
    {"measured", "1", "calibrate: points measured"},
    {"measured_rms", "1", "calibrate: rms distance from the paper's curve of the measured points"},
    {"media", "1", "media"},
    {"media_by_another_process", "1", "sweep: media stored by other processes meanwhile"},
    {"media_done", "1", "media stored so far"},
    {"media_passed", "1", "media where a droplet passed"},
    {"media_standard_error", "1", "mean_tortuosity's standard error with each medium's droplets as one cluster"},
    {"media_this_session", "1", "sweep: media this invocation stored"},
    {"media_to_do", "1", "media this invocation runs"},
    {"median", "1", "median T over the passed droplets"},
    {"medium", "", "the medium (an object of the names here), or its grain file"},
    {"medium_index", "index", "a medium's number at its porosity"},
    {"meaning", "", "columns: what a name means"},
    {"medium_seed", "1", "the seed the medium was generated from"},
    {"message", "", "why the run ended, or what the fit's optimizer said"},
    {"migrate_every", "1", "islands: generations between migrations"},
    {"migration", "", "islands: the migration topology"},
    {"min_area_ratio", "1", "smallest area_ratio over the run"},
    {"mispredictions", "1", "speculation: predictions that were wrong"},
    {"moved", "1", "grains a candidate's move moved"},
    {"moved_grain", "index", "the grain a single or relocate move moved (empty: all)"},
    {"name", "", "columns: a name softdrop writes"},
    {"objective", "", "what a candidate scores: single, mean, quantile or lower-bound"},
    {"objective_value", "1", "the search objective's value over the held-out droplets"},
    {"option", "", "history --params: an option's long name"},
    {"order", "index", "simulate --second-droplet: 1 for a pair's first droplet, 2 for the second"},
    {"outcome", "", "passed, stuck, timeout or diverged"},
    {"outcomes", "", "each candidate's outcome, in order, separated by ;"},
    {"p", "1", "fit: the log law's p"},
    {"paired", "1", "starts that passed at dt and at dt / 2"},
    {"pairs", "1", "simulate --second-droplet: pairs of droplets run"},
    {"paper", "", "fit: the paper's law against these points"},
    {"paper_tortuosity", "1", "the paper's <T> at this porosity, 1.58 - 0.58 porosity^3.87"},
    {"params", "JSON", "the options a run or sweep was started with"},
    {"parent_passed", "1", "droplets of the parent's re-run that passed"},
    {"parent_tortuosity", "1", "the value of the arrangement the candidates were made from, re-run on their starts"},
    {"pass_fraction", "1", "passed / starts"},
    {"passed", "1", "droplets that passed through"},
    {"path", "length", "the droplet's centre: rows of x, y"},
    {"path_time", "time", "the times of the path's rows"},
    {"per_medium_standard_error", "1", "per_medium_tortuosity's standard error over media"},
    {"per_medium_tortuosity", "1", "each medium's <T> first, then their mean over the media"},
    {"permeability", "length^2", "Darcy's k of the pore image's creeping flow"},
    {"periodic", "1", "1 if the box is periodic in x"},
    {"phase", "", "above, inside or below the medium"},
    {"pixel", "length", "tortuosity: a pixel's side"},
    {"pixels", "1", "tortuosity: pixels across the width"},
    {"pixels_per_smallest_radius", "1", "tortuosity: pixels across the smallest grain's radius, at each resolution"},
    {"point", "index", "a point's number along a stored path"},
    {"points", "1", "fit: points fitted"},
    {"porosity", "1", "the medium's exact pore area over its box (a mean over media where a row holds several)"},
    {"porosity_index", "index", "a porosity's number in the sweep"},
    {"porosity_standard_error", "1", "porosity's standard error over the group"},
    {"power", "", "fit: the law T = a - c porosity^b fitted (an object of the names here)"},
    {"predictions", "1", "speculation: outcomes predicted"},
    {"predictions_ahead", "1", "speculation: generations predicted ahead"},
    {"pressure", "f h", "tortuosity: the flow's pressure (f force per volume, h the pixel)"},
    {"preferred", "", "fit: the law with the lower aic (empty: either has no degrees of freedom)"},
    {"q1", "1", "first quartile of T over the passed droplets"},
    {"q3", "1", "third quartile of T over the passed droplets"},
    {"quantity", "", "tortuosity --csv: which tortuosity the row holds"},
    {"r", "length", "a grain's radius"},
    {"re_runs", "1", "re-runs on fresh starts that best_tortuosity is the mean of"},
    {"reason", "", "why a droplet's run ended"},
    {"reduced_chi2", "1", "fit: chi2 / dof"},
    {"released", "1", "simulate --second-droplet: second droplets released"},
    {"released_at", "time", "--second-droplet: when the second droplet was released, since the first began"},
    {"residuals", "1", "fit: (point - law) / error, per point"},
    {"resting_travel", "length", "calibrate: how far the droplet moved once at rest"},
    {"rms_distance", "1", "calibrate: rms distance of the points from the paper's curve, in errors"},
    {"route_tortuosity", "1",
     "T of the route: the path with the medium's shaking averaged out (once a period); T if it never shook"},
    {"run", "id", "a search run's id (simulate --format json: the one droplet's record)"},
    {"runs", "", "one record per droplet (simulate, validate, held_out)"},
    {"s0", "length^2", "the droplet's area when it reached the medium"},
    {"score", "1", "calibrate: the setting's score (lower is better)"},
    {"seconds", "s", "wall time"},
    {"seed", "1", "the random seed"},
    {"setting", "", "calibrate: the setting's name"},
    {"shaken_at", "time", "when the medium began to shake (empty: it never did; vibration-amplitude)"},
    {"shared_touched", "1", "--second-droplet: grains touched by both droplets of the pair"},
    {"slides", "1", "rigid descent: grain surfaces it slid along"},
    {"source", "", "validate: where the medium came from"},
    {"speculation", "", "optimize: the speculative drive's counts (an object of the names here)"},
    {"standard_error", "1", "the row's mean_tortuosity's standard error, each passed droplet independent"},
    {"start", "index", "a start's number among the held-out starts"},
    {"start_x", "length", "where the droplet's centre started across the top"},
    {"starts", "1", "random starts"},
    {"state", "JSON", "the search strategy's state after the generation"},
    {"status", "", "running, finished (sweeps: complete) or interrupted"},
    {"steps", "1", "time steps simulated"},
    {"steps_per_second", "1/s", "time steps over wall time"},
    {"strategy", "", "the search strategy: paper, es, lahc, anneal or cmaes"},
    {"stuck", "1", "droplets that came to rest inside the medium"},
    {"stuck_fraction", "1", "stuck / droplets"},
    {"sweep", "id", "a sweep's id"},
    {"target_generations", "1", "the generation the search runs to"},
    {"target_porosity", "1", "the porosity asked for"},
    {"termination", "", "why the search ended"},
    {"threads", "1", "threads used"},
    {"time", "time", "simulated time since the droplet was released"},
    {"timeout", "1", "droplets that ran out of steps"},
    {"tortuosity", "1", "T: the length of the droplet's path inside the medium over the medium's height"},
    {"touched", "1",
     "grains the droplet touched, a count (in a grain's row: 1 if it touched that grain); in an image medium, the "
     "connected parts of its solid"},
    {"touched_grains", "index", "the indices of the grains the droplet touched"},
    {"trace", "", "the area trace: rows of time, area, area_ratio"},
    {"trace_passed", "1", "calibrate: trace runs that passed"},
    {"trace_runs", "1", "calibrate: droplets traced"},
    {"units", "1", "a sweep's units of work (media)"},
    {"unit", "", "columns: a name's unit"},
    {"updated", "UTC time", "when the record was last written"},
    {"value", "", "the option's value (history --params), a coefficient (fit), a tortuosity (tortuosity --csv)"},
    {"values", "1", "tortuosity: the values at the two resolutions"},
    {"velocity_x", "f h^2 / mu", "tortuosity: the flow's x velocity at each pixel (NaN in the solid)"},
    {"velocity_y", "f h^2 / mu", "tortuosity: the flow's y velocity at each pixel (NaN in the solid)"},
    {"version", "", "the softdrop version that wrote the record"},
    {"walls", "", "validate: the box's side walls"},
    {"wall_seconds", "s", "the command's wall time"},
    {"warning", "", "fit: what makes the law's errors doubtful"},
    {"width", "length", "the medium's width W"},
    {"within", "1", "calibrate: points within their error of the paper's curve"},
    {"x", "length", "horizontal position"},
    {"y", "length", "height (0 at the bottom of the medium)"},
};

// The droplet parameters' columns, each with its option's key.
const std::map<std::string, std::string, std::less<>>& droplet_columns() {
  static const std::map<std::string, std::string, std::less<>> names = [] {
    std::map<std::string, std::string, std::less<>> m;
    const DropletParams p;
    visit_droplet_fields([&](const DropletField& field, const auto&) { m.emplace(column_name(field.key), field.key); },
                         p);
    return m;
  }();
  return names;
}

}  // namespace

std::string column_name(std::string option_key) {
  std::replace(option_key.begin(), option_key.end(), '-', '_');
  return option_key;
}

const std::vector<ColumnName>& column_names() {
  static const std::vector<ColumnName> sorted = [] {
    std::vector<ColumnName> v = kColumns;
    std::sort(v.begin(), v.end(),
              [](const ColumnName& a, const ColumnName& b) { return std::string_view(a.name) < b.name; });
    return v;
  }();
  return sorted;
}

bool is_column_name(std::string_view name) {
  const std::vector<ColumnName>& all = column_names();
  const auto at = std::lower_bound(all.begin(), all.end(), name, [](const ColumnName& c, std::string_view n) {
    return std::string_view(c.name) < n;
  });
  return (at != all.end() && at->name == name) || droplet_columns().count(name) > 0;
}

void check_column_names(const std::vector<std::string>& names) {
  for (const std::string& n : names)
    if (!is_column_name(n))
      throw std::logic_error("column '" + n + "' is not in softdrop's names (src/cli/columns.cpp)");
}

void check_csv_header(std::string_view header) {
  std::vector<std::string> names;
  for (std::size_t at = 0;;) {
    const std::size_t comma = header.find(',', at);
    names.emplace_back(header.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at));
    if (comma == std::string_view::npos) break;
    at = comma + 1;
  }
  check_column_names(names);
}

CLI::App* add_columns_command(CLI::App& app, ColumnsArgs& a) {
  CLI::App* s = app.add_subcommand("columns",
                                   "The names of softdrop's CSV columns, JSON keys, database views and Python "
                                   "frames, with units and meanings");
  s->fallthrough();
  s->add_option("names", a.names, "Only these names");
  s->add_option("--format", a.format, "table, csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  s->footer(
      "One quantity has one name everywhere. Droplet parameters are named by their long option with _ for - "
      "(calibrate's columns). Units: 1 dimensionless; length, time and mass in the model's units (docs/model.md); "
      "s wall-clock seconds; index a 0-based number; id a database id from 1.");
  return s;
}

int run_columns(const ColumnsArgs& a) {
  for (const std::string& n : a.names)
    if (!is_column_name(n)) throw std::invalid_argument("names: '" + n + "' is not a name softdrop writes");
  Table t;
  t.header = {"name", "unit", "meaning"};
  for (const ColumnName& c : column_names())
    if (a.names.empty() || std::find(a.names.begin(), a.names.end(), c.name) != a.names.end())
      t.rows.push_back({c.name, c.unit, c.meaning});
  for (const auto& [name, key] : droplet_columns())
    if (a.names.empty() || std::find(a.names.begin(), a.names.end(), name) != a.names.end())
      t.rows.push_back({name, "", "droplet parameter (--" + key + "; docs/model.md)"});
  t.print(std::cout, a.format);
  return 0;
}

}  // namespace softdrop::cli
