#pragma once
/// \file simulation.hpp
/// One droplet pushed by gravity through a medium: the step as named stages, exit conditions,
/// tortuosity of the centre-of-mass path and optional traces; and two droplets, one after the other.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"

namespace softdrop {

// What the library's step reads, defined in its sources: the droplets' shared model (parameters,
// the step's constants, the grain grid) and one droplet's runtime state.
struct DropletModel;
struct DropletRuntime;

/// Why a run ended.
enum class Outcome {
  passed,   ///< centre of mass went below y = 0
  stuck,    ///< no net downward progress of stuck_distance within stuck_window (or at rest)
  timeout,  ///< max_steps spent
  diverged  ///< NaN, inverted (area <= 0) or self-intersecting ring
};
const char* to_string(Outcome outcome);
/// Parses the names to_string gives; throws std::invalid_argument naming the value.
Outcome parse_outcome(const std::string& name);

/// What to run and what to record.
struct RunOptions {
  std::int64_t max_steps = 12'000'000;  ///< step budget (timeout): 72 time units at the default dt
  double stuck_window = 0.5;            ///< time window of the stuck test (time units)
  double stuck_distance = 5.0;          ///< downward progress required per window (length)
  /// The rest test, which ends a stuck droplet early: a centre of mass that travelled less than
  /// rest_distance in all, in any direction, within rest_window (time units; 0: no rest test) is
  /// at rest, and the run ends stuck. A droplet bouncing off a grain or squeezing slowly through a
  /// throat still travels, so it is left to the stuck test. A passed droplet's T and steps do not
  /// depend on it. The default, 0.1 within 0.05, is the trade results/stuck_test/ measured: no
  /// verdict changed there, and stuck droplets end several times sooner.
  double rest_window = 0.05;
  double rest_distance = 0.1;  ///< (length units)
  int check_interval = 64;     ///< steps between self-intersection / grain-inside checks
  /// Record the centre-of-mass path every this many steps (0: no path). The tortuosity always uses
  /// every step, whatever this is.
  int path_interval = 0;
  int area_interval = 0;               ///< record the ring area S(t) every this many steps (0: no)
  std::vector<double> snapshot_times;  ///< record the ring boundary at these times (time units)
  /// Polled every check_interval steps; when it returns true the run stops by throwing
  /// RunCancelled (used to drop speculative work that became useless). Empty: never.
  std::function<bool()> cancelled;

  bool IsValid(std::string* why) const;
};

/// Thrown by Simulation::run when RunOptions::cancelled returns true.
struct RunCancelled : std::exception {
  const char* what() const noexcept override { return "run cancelled"; }
};

/// A recorded ring boundary.
struct Snapshot {
  double time = 0;
  std::vector<double> x, y;
};

/// The result of one run and why it ended (cf. Ceres' Solver::Summary).
struct RunSummary {
  Outcome outcome = Outcome::timeout;
  std::string reason;      ///< one line saying why the run ended
  std::int64_t steps = 0;  ///< steps taken
  double tortuosity = 0;   ///< T = path length between y = H and y = 0 over H (passed only)
  /// T of the route: the path with the medium's shaking averaged out, the centre taken once a
  /// shaking period (at the first step of each) from when the shaking began; T itself for a run
  /// the medium never shook (passed only).
  double route_tortuosity = 0;
  double path_length = 0;  ///< length of the centre-of-mass path inside the medium so far
  /// Where the run began: the placement (Simulation::run's cx and the start height), so that a run
  /// from start_x gives the same bits again; the centre of mass for run_from_current.
  double start_x = 0, start_y = 0;
  std::vector<std::int32_t> touched;  ///< indices of grains touched, ascending
  // Diagnostics, checked every step (area, penetration) or every check_interval steps.
  double min_area_ratio = 1;       ///< smallest S / S0 seen
  double max_penetration = 0;      ///< deepest a mass went inside a grain (length)
  bool grain_inside_ring = false;  ///< a grain centre was found inside the ring
  /// When the medium began to shake (time units since the run began; DropletParams::vibrates),
  /// NaN if it never did.
  double shaken_at = std::numeric_limits<double>::quiet_NaN();
  // Optional traces.
  std::vector<double> path_t, path_x, path_y;  ///< centre of mass every path_interval steps
  std::vector<double> area_t, area;            ///< ring area every area_interval steps
  std::vector<Snapshot> snapshots;
};

/// A droplet in a medium. What its droplets share (parameters, the step's constants, the grain
/// grid) is fixed at construction; the runtime state is reset by `place` and advanced by `step`,
/// which allocates nothing. A copy shares the first's fixed part and has its own state.
class Simulation {
 public:
  /// The medium must outlive the simulation. Throws std::invalid_argument for invalid params.
  Simulation(const DropletParams& params, const Medium& medium);
  /// A temporary medium would be gone before the first step: refused at compile time.
  Simulation(const DropletParams& params, Medium&& medium) = delete;
  Simulation(const Simulation& other);
  Simulation& operator=(const Simulation& other);
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  /// Puts the inflated droplet at rest with its centre at (cx, cy) and clears the touched set.
  void place(double cx, double cy);
  /// The usual start: centre x = cx, just above the medium (clear of the highest grain).
  void place_above(double cx);
  /// Advances one time step: gravity, springs, gas pressure, the shaking (only within a run that
  /// shakes the medium), collisions, internal viscosity,
  /// position Verlet, the length constraint and the contact limit (docs/model.md), in that order.
  /// Returns false if the state became invalid (NaN or area <= 0).
  bool step();
  /// The force stages of a step on their own (gravity to viscosity): clears and accumulates all
  /// forces into state().fx/fy without moving anything.
  void compute_forces();

  /// Places the droplet above the medium at x = cx and runs to an outcome.
  RunSummary run(double cx, const RunOptions& options);
  /// Runs from the current state.
  RunSummary run_from_current(const RunOptions& options);

  const DropletState& state() const;
  /// The state to change between steps (a change made after the next step has begun is not seen).
  DropletState& mutable_state();
  const DropletParams& params() const;
  const Medium& medium() const;
  /// The ring's area as the last step measured it.
  double area() const;
  /// The resting area S0.
  double initial_area() const;
  /// Centre of mass (mean of positions, masses are equal).
  void centre_of_mass(double* cx, double* cy) const;
  /// Deepest penetration of a mass into a grain during the last step (length).
  double last_penetration() const;
  /// The y at which place_above puts the centre.
  double start_height() const;
  /// FNV-1a hash of the bits of the runtime state: the determinism fingerprint.
  std::uint64_t state_hash() const;
  /// step()'s validity test of the state the last step left: finite, with a positive area.
  bool valid() const;

  /// The library's access to the step (the types are defined in its sources, not installed).
  const DropletModel& model() const { return *model_; }
  DropletRuntime& runtime() { return *runtime_; }
  const DropletRuntime& runtime() const { return *runtime_; }

 private:
  std::shared_ptr<const DropletModel> model_;
  std::unique_ptr<DropletRuntime> runtime_;
};

// ---- Two droplets, one after the other -------------------------------------------------------
//
// The second is released above the medium once the first has gone a set distance into it (or after
// a set delay), and the two rings collide with each other as they collide with grains
// (docs/model.md, "Two droplets").
/// When the second droplet is released.
enum class SecondRelease {
  distance,  ///< once the first's centre is `after` length units below its start
  delay      ///< `after` time units after the first began
};
const char* to_string(SecondRelease release);
/// Parses "distance" / "delay"; throws std::invalid_argument naming the value.
SecondRelease parse_second_release(const std::string& name);

/// The second droplet: the same droplet as the first (DropletParams), placed above the medium at
/// the first's start x plus offset_x and held there until its release. It is released at the first
/// step at which its rule holds and its ring is clear of the first's by max_depth (bounding boxes),
/// and at once when the first's run has ended.
struct SecondDroplet {
  SecondRelease release = SecondRelease::distance;
  /// The first's descent below its start (length units), or the delay (time units). The default
  /// lets the first go four radii of the default droplet into the box.
  double after = 40;
  double offset_x = 0;  ///< the second's start x minus the first's (length units)

  /// after finite and > 0, offset_x finite; and a release rule that cannot start the second ring
  /// overlapping the first: a descent of at least 2 R + max_depth, or a delay in which free fall
  /// covers that (|g| t^2 / 2), unless offset_x alone keeps the rings that far apart. A shaken
  /// medium shakes for both on one clock, from whichever run begins it (RunStepper::join_shaking).
  bool IsValid(const DropletParams& droplet, std::string* why) const;
};

/// The two runs. Each droplet's run is a run of its own (RunOptions apply to each, its steps and
/// times counted from its own start), with two changes: a droplet's stuck or rest verdict does not
/// end it while the other droplet still moves (it may push it free); the droplet is held, its
/// stuck window starts again, and held_at records when. And a droplet that leaves the medium is
/// no longer stepped.
struct TwoDropletSummary {
  RunSummary first;
  RunSummary second;  ///< outcome timeout, 0 steps, and a reason saying so if never released
  bool released = false;
  /// When the second was released, in time units since the first began; NaN if never.
  double released_at = std::numeric_limits<double>::quiet_NaN();
  /// When each was first held (time units since its own start); NaN if never.
  double first_held_at = std::numeric_limits<double>::quiet_NaN();
  double second_held_at = std::numeric_limits<double>::quiet_NaN();
  std::int64_t contact_steps = 0;  ///< steps in which a mass of one ring was in contact with the other
  int shared_touched = 0;          ///< grains that both touched
};

/// Runs the two droplets through `medium`, the first from start x = x0. Throws
/// std::invalid_argument for invalid parameters, options or second droplet, naming it.
TwoDropletSummary run_two_droplets(const DropletParams& droplet, const Medium& medium, double x0,
                                   const RunOptions& options, const SecondDroplet& second);

/// Length of the polyline (xs, ys) between its first downward crossing of y = top and its first
/// crossing of y = 0 (crossing points interpolated), divided by `top`. Returns 0 if it does not
/// cross both. Used to cross-check the on-line accumulator in Simulation.
double polyline_tortuosity(const std::vector<double>& xs, const std::vector<double>& ys, double top);

}  // namespace softdrop
