// The search's objectives (softdrop/search.hpp): their starts and how K droplets become one value.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "softdrop/search.hpp"
#include "util/enum_names.hpp"
#include "util/quantile.hpp"
#include "util/random.hpp"
#include "util/validation.hpp"

namespace softdrop {
namespace {
constexpr detail::EnumName<ObjectiveKind> kObjectives[] = {{ObjectiveKind::single, "single"},
                                                           {ObjectiveKind::mean, "mean"},
                                                           {ObjectiveKind::quantile, "quantile"},
                                                           {ObjectiveKind::lower_bound, "lower-bound"}};
// Tags the starts' stream apart from the moves' streams derive_seed(derive_seed(seed, g), k),
// k < lambda <= 4096, and annealing's k = lambda.
constexpr std::uint64_t kStartsStream = 0x5354415254530000ULL;  // "STARTS"
}  // namespace

const char* to_string(ObjectiveKind kind) { return detail::name_of(kObjectives, kind); }
ObjectiveKind parse_objective(const std::string& name) { return detail::parse_name(kObjectives, name, "objective"); }
std::vector<std::string> objective_names() { return detail::name_list(kObjectives); }

bool ObjectiveOptions::IsValid(std::string* why) const {
  if (starts < 1 || starts > kMaxObjectiveStarts)
    return detail::fail(
        why, "starts = " + std::to_string(starts) + ": must be in [1, " + std::to_string(kMaxObjectiveStarts) + "]");
  if (!(quantile > 0 && quantile < 1))
    return detail::fail(why, "quantile = " + detail::num(quantile) + ": must be in (0, 1)");
  if (!(se_factor >= 0) || !std::isfinite(se_factor))
    return detail::fail(why, "se-factor = " + detail::num(se_factor) + ": must be >= 0");
  if (!(margin >= 0) || !std::isfinite(margin))
    return detail::fail(why, "margin = " + detail::num(margin) + ": must be >= 0");
  return true;
}

std::vector<double> objective_starts(const ObjectiveOptions& objective, std::uint64_t seed, std::int64_t generation,
                                     const Medium& medium, const DropletParams& droplet) {
  if (!objective.robust()) return {0.5 * medium.width};
  const double lo = medium.periodic ? 0.0 : droplet.radius;
  const double span = (medium.periodic ? medium.width : medium.width - 2 * droplet.radius);
  Rng rng(derive_seed(derive_seed(seed, static_cast<std::uint64_t>(generation)), kStartsStream));
  std::vector<double> x(static_cast<std::size_t>(objective.starts));
  const double k = objective.starts;
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = lo + span * ((static_cast<double>(j) + rng.uniform()) / k);
  return x;
}

double objective_value(const ObjectiveOptions& objective, const std::vector<RunSummary>& runs) {
  if (runs.empty()) throw std::invalid_argument("objective_value: no runs");
  if (!objective.robust()) return runs.front().outcome == Outcome::passed ? runs.front().tortuosity : 0.0;
  std::vector<double> t;
  t.reserve(runs.size());
  for (const RunSummary& r : runs) t.push_back(r.outcome == Outcome::passed ? r.tortuosity : 1.0);
  const double n = static_cast<double>(t.size());
  double sum = 0;
  for (double v : t) sum += v;
  const double mean = sum / n;
  switch (objective.kind) {
    case ObjectiveKind::mean:
      return mean;
    case ObjectiveKind::quantile: {
      std::sort(t.begin(), t.end());
      return detail::linear_quantile(t, objective.quantile);
    }
    case ObjectiveKind::lower_bound: {
      if (t.size() < 2) return mean;
      double ss = 0;
      for (double v : t) ss += (v - mean) * (v - mean);
      return mean - objective.se_factor * std::sqrt(ss / (n - 1) / n);
    }
    case ObjectiveKind::single:
      break;
  }
  throw std::logic_error("objective_value: unknown objective");
}

}  // namespace softdrop
