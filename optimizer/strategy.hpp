#pragma once
/// \file strategy.hpp
/// Search strategies. A strategy proposes the candidates of each generation, takes their
/// evaluations and says which candidate it keeps as the arrangement it moves on from. The drive,
/// its threads and lanes, and the history serve every strategy through this interface alone.
///
/// Every strategy is deterministic: its candidates depend only on its options, its state and the
/// generation number (random numbers come from streams derived from the seed and the generation),
/// so a search resumed from the stored state continues bit for bit.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "softdrop/search.hpp"

namespace softdrop {

class Strategy {
 public:
  virtual ~Strategy() = default;

  /// The options it was made with (options.lambda candidates a generation).
  virtual const SearchOptions& options() const = 0;
  /// The arrangement the next candidates are made from, with its evaluation (its touched grains
  /// are the ones single moves choose from: the paper's insight, kept by every strategy).
  virtual const Configuration& current() const = 0;
  /// Candidate k of `generation` (made, not evaluated), k in [0, options.lambda).
  virtual Candidate propose(std::int64_t generation, int k) const = 0;
  /// The candidates of `generation`: propose(generation, k) for every k, in index order.
  std::vector<Candidate> propose(std::int64_t generation) const;
  /// Takes the evaluated candidates of `generation` in index order, updates the state and returns
  /// the index of the candidate kept as the new current arrangement (-1: none). A passed candidate
  /// whose T beats every arrangement kept before must be kept, so the best of a search is always
  /// an arrangement its history stores.
  int tell(std::int64_t generation, const std::vector<Candidate>& candidates);
  /// Robust objectives: the current arrangement's value on this generation's starts and its
  /// droplets' T, told before the candidates, which are compared with them.
  virtual void remeasure(double value, const std::vector<double>& values) = 0;
  /// The state beyond the current arrangement, as a JSON object; "" when there is none. Stored
  /// with every generation and handed back to make_strategy on resume.
  virtual std::string state() const = 0;
  /// Whether the drive may evaluate later generations ahead of this one's decision: true when
  /// tell() depends on a generation only through which candidates improve on current() and their
  /// T, keeping the best improvement. A candidate still running can then be taken to improve on
  /// nothing until it finishes (foresee), and a generation in which none improves changes the
  /// state in a way known in advance (the paper's hill climb: not at all; es: smaller steps).
  virtual bool speculative() const { return false; }
  /// Moves on from `arrangement` (an immigrant from another island), the rest of the state as it
  /// was.
  virtual void adopt(Configuration arrangement) = 0;
  /// A copy, state and all.
  virtual std::unique_ptr<Strategy> clone() const = 0;
  /// A copy told `generation` as far as its candidates are evaluated: evaluated[k] is candidate k
  /// or nullptr while it runs (taken to pass no test: for a speculative() strategy, to improve on
  /// nothing). Sets *kept to what tell() returned. Once every candidate is there, this is tell().
  std::unique_ptr<Strategy> foresee(std::int64_t generation, const std::vector<const Candidate*>& evaluated,
                                    int* kept) const;

 protected:
  /// tell() and foresee(): candidates[k] is candidate k, or nullptr when not yet evaluated.
  virtual int decide(std::int64_t generation, const std::vector<const Candidate*>& candidates) = 0;
};

/// A strategy (options.strategy) moving on from `current`, with `state` as a previous state()
/// returned ("": a new search), or, for a strategy that resumes_by_replay(), the JSON array of
/// the state() of every generation so far, in order. Throws std::invalid_argument naming the
/// strategy if the state is not its own.
std::unique_ptr<Strategy> make_strategy(const SearchOptions& options, Configuration current, const std::string& state);

/// Whether a resumed `kind` takes every generation's state (see make_strategy) rather than the
/// last: cmaes, whose state is too large to store with each generation, stores the values it was
/// told and replays them.
bool resumes_by_replay(StrategyKind kind);

}  // namespace softdrop
