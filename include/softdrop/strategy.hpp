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

  /// The arrangement the next candidates are made from, with its evaluation (its touched grains
  /// are the ones single moves choose from: the paper's insight, kept by every strategy).
  virtual const Configuration& current() const = 0;
  /// The candidates of `generation` (made, not evaluated): options.lambda of them, in index order.
  virtual std::vector<Candidate> propose(std::int64_t generation) const = 0;
  /// Takes the evaluated candidates of `generation` in index order, updates the state and returns
  /// the index of the candidate kept as the new current arrangement (-1: none). A passed candidate
  /// whose T beats every arrangement kept before must be kept, so the best of a search is always
  /// an arrangement its history stores.
  virtual int tell(std::int64_t generation, const std::vector<Candidate>& candidates) = 0;
  /// The state beyond the current arrangement, as a JSON object; "" when there is none. Stored
  /// with every generation and handed back to make_strategy on resume.
  virtual std::string state() const = 0;
  /// Whether the drive may evaluate later generations ahead of this one's decision: true when a
  /// generation that keeps nothing changes nothing, and the kept candidate is the best strict
  /// improvement of the current arrangement (the paper's hill climb).
  virtual bool speculative() const { return false; }
};

/// A strategy (options.strategy) moving on from `current`, with `state` as a previous state()
/// returned ("": a new search). Throws std::invalid_argument naming the strategy if the state is
/// not its own.
std::unique_ptr<Strategy> make_strategy(const SearchOptions& options, Configuration current,
                                        const std::string& state);

}  // namespace softdrop
