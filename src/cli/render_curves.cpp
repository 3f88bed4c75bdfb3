// `softdrop render curves`: the best T of several searches against evaluations (or wall seconds),
// one line a search, coloured by label, for comparing strategies and seeds.
#include <array>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "cli/output.hpp"
#include "cli/render_command.hpp"
#include "softdrop/store.hpp"

namespace softdrop::cli {
namespace {

// The database's name without its folder, extension and a trailing -<seed>: searches that differ
// only in their seed share a label, and so a colour.
std::string default_label(const std::string& db) {
  std::string stem = std::filesystem::path(db).stem().string();
  const auto dash = stem.find_last_of('-');
  if (dash != std::string::npos && dash + 1 < stem.size() &&
      stem.find_first_not_of("0123456789", dash + 1) == std::string::npos)
    stem.erase(dash);
  return stem;
}

Rgba palette(std::size_t i) {
  static const std::array<Rgba, 8> colours{{{0.80, 0.10, 0.10, 1},
                                            {0.12, 0.31, 0.80, 1},
                                            {0.10, 0.55, 0.20, 1},
                                            {0.60, 0.20, 0.65, 1},
                                            {0.90, 0.55, 0.05, 1},
                                            {0.10, 0.60, 0.65, 1},
                                            {0.45, 0.30, 0.15, 1},
                                            {0.35, 0.35, 0.35, 1}}};
  return colours[i % colours.size()];
}

}  // namespace

int render_curves(RenderArgs& a) {
  if (a.dbs.empty()) throw std::invalid_argument("db: give at least one search (--db FILE, repeated)");
  if (!a.labels.empty() && a.labels.size() != a.dbs.size())
    throw std::invalid_argument("label: " + std::to_string(a.labels.size()) + " labels for " +
                                std::to_string(a.dbs.size()) + " databases (give one a database, or none)");
  const bool seconds = a.x_axis == "seconds";
  Chart chart;
  std::map<std::string, std::size_t> colour_of;  // label -> palette index, in order of appearance
  for (std::size_t i = 0; i < a.dbs.size(); ++i) {
    auto history = open_history(a.dbs[i], OpenMode::read_only);
    std::int64_t id = a.run_id;
    if (id == 0) {
      const auto runs = history->runs();
      if (runs.size() != 1)
        throw std::invalid_argument("--db '" + a.dbs[i] + "' holds " + std::to_string(runs.size()) +
                                    " runs; choose one with --run ID");
      id = runs.front().id;
    }
    const RunRecord run = history->run(id);
    const std::string label = a.labels.empty() ? default_label(a.dbs[i]) : a.labels[i];
    const bool first = colour_of.emplace(label, colour_of.size()).second;
    Series s;
    s.style = Series::Style::steps;
    s.colour = palette(colour_of[label]);
    s.width = 1.5;
    if (first) s.label = label;
    double wall = 0;
    for (const GenerationRecord& g : history->generations(id)) {
      wall += g.seconds;
      s.x.push_back(seconds ? wall : static_cast<double>(1 + g.generation * run.lambda));
      s.y.push_back(g.best_t);
    }
    chart.series.push_back(std::move(s));
  }
  chart.x_label = seconds ? "wall seconds" : "evaluations";
  chart.y_label = "best tortuosity T";
  chart.title = "best T of " + std::to_string(a.dbs.size()) + (a.dbs.size() == 1 ? " search" : " searches");
  render_chart(chart, style_of(a), a.output);
  return 0;
}

}  // namespace softdrop::cli
