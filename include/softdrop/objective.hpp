#pragma once
/// \file objective.hpp
/// What a search maximises. The paper's objective is the tortuosity of one droplet dropped at the
/// middle of the top; with the calibrated droplet that path is chaotic (moving the start by 0.01
/// changes T by 0.3), so maximising it tunes one trajectory, not the medium. The robust objectives
/// push K droplets through every arrangement, from starts that cover the top of the box, and
/// reduce their T to one number: a property of the medium.
///
/// Noise is handled with common random numbers: generation g draws K fresh starts, and every
/// candidate of g and the arrangement they were made from (re-run on the same starts) are compared
/// on those starts alone. No start is used twice, so the search cannot tune K trajectories.

#include <cstdint>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

enum class ObjectiveKind {
  single,      ///< the paper's: T of one droplet dropped at x = W/2
  mean,        ///< the mean T over the K droplets
  quantile,    ///< a lower quantile of the K values of T (risk-aware)
  lower_bound  ///< mean - se_factor x standard error of the mean (risk-aware)
};
const char* to_string(ObjectiveKind kind);
/// Parses single / mean / quantile / lower-bound; throws std::invalid_argument naming the value.
ObjectiveKind parse_objective(const std::string& name);
std::vector<std::string> objective_names();

/// Most starts one evaluation may take.
constexpr int kMaxObjectiveStarts = 4096;

struct ObjectiveOptions {
  ObjectiveKind kind = ObjectiveKind::single;
  /// K: droplets per evaluation of a robust objective, in [1, kMaxObjectiveStarts] (single: 1).
  int starts = 16;
  double quantile = 0.25;  ///< quantile: the quantile of T maximised, in (0, 1)
  double se_factor = 1;    ///< lower-bound: k in mean - k SE, >= 0
  /// Robust objectives: a candidate beats its parent only by more than this many standard errors
  /// of their droplets' paired differences of T (>= 0; 0: any gain). With lambda candidates the
  /// largest of lambda draws of noise would otherwise win most generations.
  double margin = 2;
  bool robust() const { return kind != ObjectiveKind::single; }
  /// Droplets one evaluation pushes: 1 for single, starts otherwise.
  int droplets() const { return robust() ? starts : 1; }
  /// False, with the reason naming the option, for starts outside [1, 4096], a quantile outside
  /// (0, 1), or a negative or non-finite se-factor or margin.
  bool IsValid(std::string* why) const;
};

/// The start x of every droplet of an evaluation in `generation` of a search seeded `seed`.
/// single: { W/2 }. Robust: K starts stratified over the top, droplet j uniform in the j-th of K
/// equal intervals of [0, W) (walls: [R, W - R], R the droplet's radius), drawn from a stream of
/// (seed, generation) that no move uses.
std::vector<double> objective_starts(const ObjectiveOptions& objective, std::uint64_t seed, std::int64_t generation,
                                     const Medium& medium, const DropletParams& droplet);

/// The value of the objective over the droplets' runs (one per start, in start order). A droplet
/// that did not pass counts as T = 1, a straight path: the smallest T there is, so a medium that
/// traps droplets scores less than one that lets them through, and one that traps every droplet
/// scores 1. single: the one droplet's T (0 when it did not pass, as before).
double objective_value(const ObjectiveOptions& objective, const std::vector<RunSummary>& runs);

}  // namespace softdrop
