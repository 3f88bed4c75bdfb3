// `softdrop render search`: the arrangement a search kept, with droplets' paths through it, and its
// value against generation. A robust objective's value belongs to the medium, so its picture shows
// droplets from the held-out value's random starts; the single objective's is one droplet's from
// x0 = W/2, shown as the paper shows it: that path thick, the earlier bests' paths thin.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "cli/history_command.hpp"
#include "cli/kept_arrangement.hpp"
#include "cli/output.hpp"
#include "cli/render_command.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {
namespace {

constexpr int kRobustPaths = 50;  // paths drawn by default for a robust objective

// The run's droplet and exit options, as its held-out value ran them.
SearchOptions stored_options(const RenderArgs& a, const RunRecord& run) {
  try {
    return search_params_from_json(run.params);
  } catch (const std::exception& e) {
    throw std::runtime_error("--db '" + a.db + "': run " + std::to_string(a.run_id) + ": " + e.what());
  }
}

// The in-search value against generation up to `last`, as `history --best` gives it: each
// arrangement kept, from its generation on, at the single objective's T or at a robust
// objective's value where its tenure ended (the mean of its re-runs on fresh starts). Then each
// stored held-out value of an arrangement kept by then, with its error.
Chart value_chart(const RenderArgs& a, const RunRecord& run, const std::vector<GenerationRecord>& gs,
                  const std::vector<ValidationRecord>& validations, const ArrangementValues& values,
                  std::int64_t last) {
  Series in_search;
  in_search.style = Series::Style::steps;
  in_search.colour = parse_colour(a.path_colour);
  in_search.label = values.robust() ? "in the search (the mean of its re-runs)" : "in the search (x0 = W/2)";
  // The re-runs up to `last` only: the chart of an earlier generation shows what was known then.
  const std::vector<GenerationRecord> shown(
      gs.begin(),
      gs.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(gs.size(), static_cast<std::size_t>(last) + 1)));
  for (const BestPoint& p : best_curve(shown, values.robust())) {
    in_search.x.push_back(static_cast<double>(p.generation));
    in_search.y.push_back(p.value);
  }
  in_search.x.push_back(static_cast<double>(last));  // flat to the last generation shown
  in_search.y.push_back(in_search.y.back());
  Chart chart;
  chart.series.push_back(in_search);
  Series held_out;
  held_out.style = Series::Style::points;
  held_out.colour = parse_colour(a.stuck_colour);
  held_out.width = 4;
  for (const GenerationRecord& g : gs) {
    if (g.generation > last) break;
    const std::optional<ValidationRecord> v = held_out_of(validations, g.generation);
    if (!v || !std::isfinite(v->mean_t)) continue;
    held_out.x.push_back(static_cast<double>(g.generation));
    held_out.y.push_back(v->mean_t);
    held_out.err.push_back(std::isfinite(v->standard_error) ? v->standard_error : 0.0);
    held_out.label = "held out: <T> over " + std::to_string(v->starts) + " random starts";
  }
  if (!held_out.x.empty()) chart.series.push_back(held_out);
  chart.x_label = "generation";
  chart.y_label = "tortuosity T of the best";
  chart.title = "run " + std::to_string(a.run_id) + ": " + std::to_string(run.grains) +
                " grains, λ = " + std::to_string(run.lambda);
  return chart;
}

}  // namespace

int render_search(RenderArgs& a) {
  const RenderStyle style = style_of(a);
  if (!a.curve.empty()) check_picture_path("--curve", a.curve);
  if (a.search_droplets < -1 || a.search_droplets > 10'000)
    throw std::invalid_argument("droplets = " + std::to_string(a.search_droplets) + ": must be in [0, 1e4]");
  auto history = open_history(a.db, OpenMode::read_only);
  const RunRecord run = history->run(a.run_id);
  check_stored_generation(a.generation, run);
  const Configuration best = history->configuration(a.run_id, a.generation < 0 ? run.best_generation : a.generation);
  const std::vector<GenerationRecord> generations = history->generations(a.run_id);
  const std::vector<ValidationRecord> validations = history->validations(a.run_id);
  const ArrangementValues values = arrangement_values(run, generations, validations, best);
  const int droplets = a.search_droplets >= 0 ? a.search_droplets : (values.robust() ? kRobustPaths : 0);

  Scene scene;
  scene.medium = best.medium;
  scene.filled.assign(best.medium.grains.size(), 0);
  std::string drawn;  // the caption's words for the paths
  if (droplets > 0) {
    // The first `droplets` of the held-out value's starts (validate's default starts if none is
    // stored), pushed by the run's droplet: the same droplets as that value's first ones.
    const SearchOptions stored = stored_options(a, run);
    BatchOptions batch = a.batch;
    batch.droplets = droplets;
    batch.seed = values.held_out ? values.held_out->seed : HeldOutOptions{}.seed;
    const RunOptions recorded = paths_run(stored.run, droplets, a, stored.droplet);
    const std::vector<RunSummary> runs = run_paths(stored.droplet, best.medium, recorded, batch, a);
    add_paths(scene, runs, a, 0);
    shade_by_touches(scene, runs);
    int passed = 0;
    for (const RunSummary& r : runs) passed += r.outcome == Outcome::passed;
    drawn = std::to_string(droplets) + (values.held_out ? " held-out paths (" : " paths from random starts (") +
            std::to_string(passed) + " passed), each grain shaded by the share of them that touched it";
  } else {
    for (std::int32_t i : best.eval.touched) scene.filled[static_cast<std::size_t>(i)] = 1;
    drawn = std::to_string(best.eval.touched.size()) + " grains touched (filled)";
  }
  if (!values.robust()) {
    // The in-search droplet's path thick; without held-out paths, the earlier bests' paths thin.
    Rgba thin = parse_colour(a.path_colour);
    thin.a = 0.35;
    for (const BestPoint& p : best_curve(generations, false)) {
      if (droplets > 0 || p.generation >= best.generation) break;
      const Configuration c = history->configuration(a.run_id, p.generation);
      scene.lines.push_back(path_line(c.eval.path_x, c.eval.path_y, thin, 1.0));
    }
    scene.lines.push_back(path_line(best.eval.path_x, best.eval.path_y, parse_colour(a.path_colour), 3.5));
  }
  scene.caption = "run " + std::to_string(a.run_id) + ", generation " + std::to_string(best.generation) +
                  ": T = " + fixed(values.in_search, 4) + " in the search (" + in_search_basis(values, /*brief=*/true) +
                  ")";
  if (values.held_out) scene.caption += "\nheld out: " + held_out_text(*values.held_out);
  scene.caption += "\n" + drawn + "; " + medium_caption(best.medium);
  draw_picture(scene, style, a.output);
  if (!a.curve.empty()) {
    const std::int64_t last = std::max(best.generation, a.generation < 0 ? run.generations : a.generation);
    render_chart(value_chart(a, run, generations, validations, values, last), style, a.curve);
  }
  return 0;
}

}  // namespace softdrop::cli
