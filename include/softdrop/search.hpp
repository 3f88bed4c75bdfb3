#pragma once
/// \file search.hpp
/// The maximum-tortuosity search (docs/search.md). Each generation makes candidates from
/// the current arrangement (all grains jiggle, or one grain the droplet touched moves), pushes the
/// droplet through each, and its strategy (docs/search.md) keeps one or none. The paper's strategy
/// is a hill climb: it keeps the best candidate whose tortuosity is strictly higher.
///
/// Randomness is counter-based: candidate k of generation g draws from the stream
/// derive_seed(derive_seed(seed, g), k). The generator state of a search is therefore (seed, last
/// generation) and the strategy's stored state, which makes resuming exact and results
/// independent of the thread count.
/// This module knows nothing about storage; callers log generations through the callback.
///
/// What a search maximises. The paper's objective is the tortuosity of one droplet dropped at the
/// middle of the top; with the calibrated droplet that path is chaotic (moving the start by 0.01
/// changes T by 0.3), so maximising it tunes one trajectory, not the medium. The robust objectives
/// push K droplets through every arrangement, from starts that cover the top of the box, and
/// reduce their T to one number: a property of the medium.
///
/// Noise is handled with common random numbers: generation g draws K fresh starts, and every
/// candidate of g and the arrangement they were made from (re-run on the same starts) are compared
/// on those starts alone. No start is used twice, so the search cannot tune K trajectories.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
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

/// How a candidate was made from its parent.
enum class MoveKind {
  initial,   ///< generation 0: the starting arrangement itself
  all,       ///< every grain jumps by a small random step
  single,    ///< one grain, chosen among those the parent's droplet touched, jumps
  relocate,  ///< one grain the parent's droplet did not touch is put next to the droplet's path
  migrate,   ///< islands: another island's best arrangement, kept if it beats this island's best
  mixed      ///< a generation only: its candidates were made by different moves (es draws each one's)
};
const char* to_string(MoveKind kind);
/// Parses "initial" / "all" / "single" / "relocate" / "migrate" / "mixed"; throws std::invalid_argument naming
/// the value.
MoveKind parse_move_kind(const std::string& name);

/// How a search chooses its candidates and what it keeps (docs/search.md).
enum class StrategyKind {
  paper,   ///< the paper's hill climb: keep the best candidate that beats the current arrangement
  es,      ///< (1 + lambda) evolution strategy: the paper's moves, with step sizes that adapt
  lahc,    ///< late acceptance hill climbing: also keeps candidates no worse than L generations ago
  anneal,  ///< simulated annealing: keeps a worse candidate with probability exp(dT / temperature)
  /// CMA-ES (pagmo2): lambda arrangements a generation drawn from a Gaussian over every grain
  /// centre, which adapts to the better ones; the best so far is kept apart
  cmaes
};
const char* to_string(StrategyKind kind);
/// Parses paper / es / lahc / anneal / cmaes; throws std::invalid_argument naming the value.
StrategyKind parse_strategy(const std::string& name);
/// Every strategy's name, in the enum's order.
std::vector<std::string> strategy_names();

/// The strategy and its own options; each strategy reads only its own.
struct StrategyOptions {
  StrategyKind kind = StrategyKind::paper;
  /// es: the share of candidates that should improve. A move kind's step grows when its moves
  /// succeed more often than this, and shrinks otherwise (Rechenberg's rule, whose 1/5 suits
  /// smooth problems; here far fewer moves improve, and 1/5 shrinks the steps to their floor).
  double target_success = 0.02;
  /// lahc: a candidate is kept if it is no worse than the current arrangement, or than the
  /// current arrangement of `history_length` generations before (Burke and Bykov).
  int history_length = 50;
  /// anneal: the temperature at generation 0, in units of T; it halves every `half_life`
  /// generations.
  double temperature = 0.01;
  double half_life = 1000;  ///< anneal: generations
  /// cmaes: the Gaussian's first standard deviation of every centre coordinate (length units). It
  /// adapts from there; too small a start spends the first hundreds of generations growing it.
  double sigma = 8;
  bool IsValid(std::string* why) const;
};

/// Everything that defines a search (and so must not change when it is resumed).
struct SearchOptions {
  std::uint64_t seed = 1;    ///< seed of the moves
  int lambda = 1;            ///< candidates per generation (1: exactly the paper's algorithm)
  int single_every = 10;     ///< every this-th generation moves a single touched grain (0: never)
  double step = 1.0;         ///< all-grain move: each grain jumps uniformly within this radius (length)
  double single_step = 5.0;  ///< single move: the grain jumps uniformly within this radius (length)
  /// Every this-th generation (0: never; single moves take precedence) one grain the droplet did
  /// not touch moves next to a point of the droplet's path: its centre within droplet radius + its
  /// radius of the point, where the droplet must meet it. A grain the droplet never touches adds
  /// nothing to T; put in the droplet's way it may turn the path.
  int relocate_every = 0;
  /// A jump that would break the spacing rule is redrawn up to this many times; after that the
  /// grain stays where it was (which always satisfies the rule).
  int max_redraws = 20;
  double gap = 0.13;         ///< spacing rule: surface gap >= gap x the larger radius
  StrategyOptions strategy;  ///< how candidates are chosen and kept
  /// What a candidate's evaluation measures (ObjectiveOptions, above): the paper's one droplet from the
  /// middle of the top, or K droplets from fresh starts each generation.
  ObjectiveOptions objective;
  DropletParams droplet;  ///< the droplet pushed through every candidate
  /// Exit conditions of each evaluation. path_interval is the sampling of the stored best path
  /// (steps); traces and snapshots are not used.
  RunOptions run;

  SearchOptions() { run.path_interval = 100; }
  bool IsValid(std::string* why) const;
};

/// The droplets' runs through one arrangement, reduced to what the search keeps.
struct Evaluation {
  /// passed when at least one droplet passed; otherwise the first droplet's outcome.
  Outcome outcome = Outcome::timeout;
  std::string reason;
  /// The objective's value (objective_value), meaningful when outcome == passed; for the single
  /// objective, the droplet's T.
  double tortuosity = 0;
  std::int64_t steps = 0;             ///< summed over the droplets
  std::vector<std::int32_t> touched;  ///< grains any droplet touched, ascending
  /// The first droplet's centre-of-mass path every run.path_interval steps.
  std::vector<double> path_x, path_y;
  int droplets = 0;  ///< droplets pushed (0: not evaluated)
  /// Robust objectives: each droplet's T in start order, 1 where it did not pass (not stored).
  std::vector<double> values;
  int passed = 0;      ///< droplets that passed
  double seconds = 0;  ///< wall time (not part of the deterministic result)
};

/// Pushes the droplet from the middle of the top (x = W/2, just above the highest grain): the
/// single objective, whatever options.objective says.
Evaluation evaluate(const Medium& medium, const SearchOptions& options);
/// The evaluation generation `generation` of the search makes of `medium`: the objective's
/// droplets from objective_starts(options.objective, options.seed, generation, ...). For the
/// single objective, evaluate(medium, options).
Evaluation evaluate(const Medium& medium, const SearchOptions& options, std::int64_t generation);

/// One candidate arrangement of a generation and its evaluation.
struct Candidate {
  int index = 0;  ///< k in [0, lambda)
  MoveKind kind = MoveKind::all;
  int moved_grain = -1;  ///< single moves: the grain that was chosen
  int moved = 0;         ///< grains that actually moved (the others' jumps kept being refused)
  Medium medium;
  Evaluation eval;
};

/// The best arrangement so far and the generation that found it.
///
/// With a robust objective, values of different generations come from different starts and
/// cannot be compared, and the largest of them is the luckiest. The best is then the arrangement
/// the strategy stands on, kept in `generation`; its eval.tortuosity is the mean of its values
/// in the generations since then, each a re-run on fresh starts (until the first, the value it
/// was kept with).
struct Configuration {
  std::int64_t generation = 0;
  Medium medium;
  Evaluation eval;
};

/// One generation's candidates and what became of them.
struct Generation {
  std::int64_t number = 0;
  MoveKind kind = MoveKind::all;
  std::vector<Candidate> candidates;
  int accepted = -1;   ///< index of the candidate the strategy kept (paper: the improvement), -1: none
  double best_t = 0;   ///< best tortuosity after this generation
  int touched = 0;     ///< grains touched in the best's run after this generation
  double seconds = 0;  ///< wall time of the generation
  std::string state;   ///< the strategy's state after it (JSON object; empty: none)
  /// Robust objectives: the arrangement the candidates were made from, run again on this
  /// generation's starts; the candidates were compared with this value (droplets 0: not run, the
  /// single objective). It is a fresh measurement, taken before anything was chosen on it.
  Evaluation parent;
};

/// The move kind of generation g >= 1.
MoveKind move_kind(std::int64_t generation, const SearchOptions& options);

/// Candidate `index` of `generation` made from `parent` (not evaluated). Deterministic in (seed,
/// generation, index). Every grain jump is checked with CGAL against the spacing rule and redrawn
/// if refused; the result always satisfies the rule (checked again; std::logic_error if not).
Candidate make_candidate(const Configuration& parent, std::int64_t generation, int index, const SearchOptions& options);

/// A candidate made from `parent` by a move of `kind` (all or single) whose jumps have radius
/// `radius`, drawing its random numbers from the stream `stream`; make_candidate is the paper's
/// choice of kind, radius and stream. The same guarantees as make_candidate.
Candidate make_move(const Configuration& parent, MoveKind kind, double radius, std::uint64_t stream, int index,
                    const SearchOptions& options);

/// Evaluates the starting arrangement as generation 0. Throws std::runtime_error naming the
/// outcome if the droplet does not pass, or if the arrangement breaks the spacing rule.
Generation initial_generation(const Medium& medium, const SearchOptions& options, Configuration* best);

class Strategy;

/// The search state: options, the strategy (with its current arrangement), the best so far and
/// the last generation done.
class Search {
 public:
  /// A search whose best (and current arrangement) is `best`, at generation `last_generation`.
  /// Throws std::invalid_argument for invalid options or a best that did not pass.
  Search(const SearchOptions& options, Configuration best, std::int64_t last_generation);
  /// A resumed search whose strategy moves on from `current` with the stored `state` (see
  /// Strategy::state), and whose best so far is `best`. Robust objectives: `best` is `current`
  /// with its stored mean of re-runs as T (see Configuration).
  Search(const SearchOptions& options, Configuration best, Configuration current, const std::string& state,
         std::int64_t last_generation);
  ~Search();
  Search(Search&&) noexcept;
  Search& operator=(Search&&) noexcept;

  /// Runs generation last_generation() + 1, its candidates on up to `threads` threads (0: all
  /// cores), `lanes` stepped together on each (0: the default), and updates the best. The result
  /// does not depend on `threads` or `lanes`.
  Generation next(int threads = 0, int lanes = 0);
  /// Completes generation last_generation() + 1 from its evaluated candidates (all lambda of them,
  /// in index order): the strategy keeps one or none, and the best is updated. next() and the
  /// pipelined drive both end here. Robust objectives: `parent` is the current arrangement
  /// evaluated on the generation's starts, and the candidates are compared with it.
  Generation complete(std::vector<Candidate> candidates, double seconds, Evaluation parent = {});
  /// Generation last_generation() + 1 as a migration (the island model, docs/search.md): its one candidate is
  /// `immigrant` (an arrangement another island evaluated with the same options), kept, as best
  /// and as the arrangement the strategy moves on from (its state otherwise unchanged), if its T
  /// beats this search's best. Robust objectives: the immigrant and the current arrangement run
  /// again on the generation's starts (its parent), and the immigrant must beat it there, as a
  /// candidate must.
  Generation immigrate(const Configuration& immigrant);

  const Configuration& best() const { return best_; }
  const Strategy& strategy() const { return *strategy_; }
  std::int64_t last_generation() const { return last_; }
  const SearchOptions& options() const { return options_; }

 private:
  Generation complete_robust(std::vector<Candidate> candidates, double seconds, Evaluation parent);
  // Generation last_ + 1 with its candidates (lambda of them, or std::logic_error).
  Generation open_generation(std::vector<Candidate> candidates) const;
  // Records the generation as done: the best after it, its time and the strategy's state.
  void close_generation(Generation& g, double seconds);
  // Robust objectives: one more re-run of the best on fresh starts, into its mean.
  void rerun_best(double fresh);
  SearchOptions options_;
  Configuration best_;
  std::unique_ptr<Strategy> strategy_;
  std::int64_t last_;
  std::int64_t remeasured_ = 0;  // robust: the generations since best_ was kept, each re-running it
};

/// Why `drive` stopped.
enum class Termination {
  generations,  ///< the requested generation was reached
  time_limit,   ///< the time budget ran out (checked between generations)
  interrupted,  ///< the stop flag was raised (Ctrl-C); the generation in flight was finished
  callback      ///< a callback asked to stop
};
const char* to_string(Termination termination);

/// When to stop.
struct DriveOptions {
  std::int64_t generations = 100;           ///< run up to this generation number
  double time_limit = 0;                    ///< wall seconds (0: none)
  const std::atomic<bool>* stop = nullptr;  ///< raised asynchronously to stop after the generation
  int threads = 0;                          ///< 0: all cores
  /// Threads (or, on one thread, its lanes) evaluate candidates of the next generations before
  /// the current one is decided, assuming it accepts nothing (most generations), and drop them
  /// when it does accept. Once a finished candidate of a generation beats its parent, they go on
  /// from that candidate instead (and drop that work if another candidate wins, or an earlier
  /// generation accepts after all).
  /// The history is the same as without it; it only keeps threads busy.
  bool speculate = true;
  /// Candidates each speculating thread steps together, in [1, 64]; 0: chosen
  /// for the processor, the threads, λ and the constraint order. A matter of speed only: the
  /// history does not depend on it.
  int lanes = 0;

  /// False, with the reason naming the option, for lanes outside [0, 64].
  bool IsValid(std::string* why) const;
};

/// What the speculating evaluation did besides the history: work that did not count.
struct SpeculationStats {
  int threads = 0;  ///< worker threads of the pipeline (0: it did not speculate)
  int lanes = 0;    ///< candidates each stepped together (DriveOptions::lanes, or its default)
  /// Evaluations begun and then dropped, finished or cancelled mid-run, because they were made
  /// from a parent their generation did not have (not counting those cut short by the end).
  std::int64_t dropped = 0;
  /// Steps the dropped evaluations had taken when they were dropped (a cancelled run stops at its
  /// next check, every RunOptions::check_interval steps): the speculation's cost.
  std::int64_t dropped_steps = 0;
  /// Steps of the evaluations that reached their generations (those of the history).
  std::int64_t kept_steps = 0;
  /// Times the pipeline went on from a finished candidate that beat its generation's parent before
  /// that generation was complete. The parent is the best, or for a generation after an undecided
  /// one, what the predictions before it make the best.
  std::int64_t predictions = 0;
  /// Predictions that did not come true: overturned by a candidate of the same generation that
  /// finished later and won, or ended with their parent by a prediction for an earlier generation.
  /// A drive that reaches its last generation has predictions == accepted + mispredictions.
  std::int64_t mispredictions = 0;
  /// Predictions for a generation after the next one to complete: made from the parent the
  /// predictions before it give, while those were not yet settled.
  std::int64_t predictions_ahead = 0;
};

/// What a drive did and why it ended (cf. Ceres' Solver::Summary).
struct SearchSummary {
  Termination termination = Termination::generations;
  std::string message;  ///< one line
  std::int64_t last_generation = 0;
  std::int64_t generations_run = 0;
  std::int64_t evaluations = 0;
  std::int64_t droplets = 0;  ///< droplet runs: evaluations x the objective's droplets, and the re-runs
  std::int64_t accepted = 0;
  double seconds = 0;
  double best_t = 0;
  SpeculationStats speculation;  ///< all zero without speculation
  double evaluations_per_second() const { return seconds > 0 ? static_cast<double>(evaluations) / seconds : 0; }
};

/// Called after each generation; returns false to stop. The logging hook (the history store and
/// the progress line live in callbacks, so the search knows nothing of them).
using GenerationCallback = std::function<bool(const Generation&, const Configuration& best)>;

/// Runs generations until a stop condition holds. Results do not depend on threads or speculate.
SearchSummary drive(Search& search, const DriveOptions& options, const GenerationCallback& callback);

}  // namespace softdrop
