#pragma once
// What evaluating a candidate means, shared by the search's one-generation-at-a-time path
// (search.cpp) and its speculating drive (drive.cpp, speculative_pipeline.cpp). Internal to softdrop_opt.
#include <chrono>
#include <vector>

#include "sim/lane_policy.hpp"
#include "softdrop/search.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::detail {

// Whether a candidate's evaluation makes it the best so far: a strict improvement of a passed
// droplet (ties go to the earlier candidate, so the choice does not depend on threads).
inline bool improves(const Evaluation& e, double best_t) {
  return e.outcome == Outcome::passed && e.tortuosity > best_t;
}

// Whether `e` beats `parent` (the arrangement it was made from, evaluated on the same starts).
// single: improves(e, parent.tortuosity). Robust: its value must also exceed the parent's by more
// than objective.margin standard errors of the droplets' paired differences of T, so that the
// largest of lambda draws of noise is not taken for a better medium.
bool improves(const Evaluation& e, const Evaluation& parent, const ObjectiveOptions& objective);

// Pointers to every candidate, in their order: the form best_improvement and Strategy's decisions
// take.
inline std::vector<const Candidate*> pointers(const std::vector<Candidate>& candidates) {
  std::vector<const Candidate*> out;
  for (const Candidate& c : candidates) out.push_back(&c);
  return out;
}

// The candidate that improves on `t` the most (the earliest on a tie), -1 if none improves;
// nullptr stands for a candidate not yet evaluated.
inline int best_improvement(const std::vector<const Candidate*>& candidates, double t) {
  int best = -1;
  for (const Candidate* c : candidates)
    if (c && improves(c->eval, t)) t = c->eval.tortuosity, best = c->index;
  return best;
}

// The candidate that beats `parent` with the highest value (the earliest on a tie), -1 if none.
int best_improvement(const std::vector<const Candidate*>& candidates, const Evaluation& parent,
                     const ObjectiveOptions& objective);

// The run options of an evaluation: no area trace, no snapshots.
RunOptions evaluation_run(const RunOptions& run);

// A run's summary reduced to what the search keeps; t0 is when the evaluation began.
Evaluation as_evaluation(RunSummary&& s, std::chrono::steady_clock::time_point t0);
// The droplets' runs of one evaluation (in start order) reduced to what the search keeps (see
// Evaluation); one run of the single objective gives as_evaluation's bits.
Evaluation as_evaluation(const ObjectiveOptions& objective, std::vector<RunSummary>&& runs,
                         std::chrono::steady_clock::time_point t0);

// Evaluates every candidate (as evaluate(medium, options, generation) does, to the bit) on up to
// `threads` threads (0: all cores), stepping up to `lanes` droplets together on each (0: enough
// to share the droplets out, at most interleaved_lanes()).
void evaluate_candidates(std::vector<Candidate>& candidates, const SearchOptions& options, std::int64_t generation,
                         int threads, int lanes);

}  // namespace softdrop::detail
