#pragma once
// TwoDropletRun: two droplets' runs stepped together (run_two_droplets), a step at a time, so that
// a test can look at both rings between steps. Private to the library.
#include <cstdint>
#include <optional>
#include <vector>

#include "ring_contact.hpp"
#include "run_stepper.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

class TwoDropletRun {
 public:
  /// Places both droplets (the second held above the medium) and begins the first's run. Throws
  /// std::invalid_argument as run_two_droplets does.
  TwoDropletRun(const DropletParams& droplet, const Medium& medium, double x0, const RunOptions& options,
                const SecondDroplet& second);
  TwoDropletRun(const TwoDropletRun&) = delete;
  TwoDropletRun& operator=(const TwoDropletRun&) = delete;

  /// The lanes the pair holds in a driver that steps several (run_pairs_interleaved): one for each
  /// droplet still running, and one for the second before its release.
  int lanes_held() const {
    const int second = second_run_ ? (second_running() ? 1 : 0) : (finished() ? 0 : 1);
    return (first_run_->finished() ? 0 : 1) + second;
  }
  /// Both runs have ended (or the first has, and the second could not be released).
  bool finished() const { return first_run_->finished() && (!second_run_ || second_run_->finished()); }
  /// One step of every droplet still running, with the ring-ring stages while both are (a
  /// RingGroup of the two rings); then each run's book-keeping, and the second's release if it is
  /// due: begin_step(), the step, end_step().
  void step();
  /// A step in parts, for a driver that steps several pairs' rings together (a lane-by-lane block):
  /// begin_step() sets the holds and gives the rings to step, the first droplet's and the second's
  /// (null: not stepped); the driver steps them, with the ring-ring stages between them (and this
  /// pair's scratch()) where both are; end_step(moved) does the rest, given what the ring limit
  /// moved.
  void begin_step(Simulation** a, Simulation** b);
  void end_step(int moved);
  RingContactScratch* scratch() { return &scratch_; }
  /// The summaries, once finished().
  TwoDropletSummary take();

  const Simulation& first() const { return first_; }
  const Simulation& second() const { return second_; }
  bool first_running() const { return !first_run_->finished(); }
  bool second_running() const { return second_run_ && !second_run_->finished(); }
  /// Masses the last step's ring limit moved.
  int limited() const { return limited_; }

 private:
  void release_if_due();
  // The medium is one: once either droplet's run begins to shake it, both shake on its clock.
  void share_shaking();

  Simulation first_, second_;
  RunOptions options_;
  SecondDroplet rule_;
  double x0_ = 0, x1_ = 0;  // the starts
  std::optional<RunStepper> first_run_, second_run_;
  RingContactScratch scratch_;
  std::int64_t k_ = 0, contact_steps_ = 0;
  std::int64_t shaken_from_ = -1;  // the pair's step at which the medium began to shake; -1: not yet
  double released_at_;
  int limited_ = 0;
  bool a_on_ = false, b_on_ = false;        // the rings the step in progress moves
  std::vector<DropletState*> group_rings_;  // the ring group's scratch
  std::vector<int> group_corrections_;
};

}  // namespace softdrop
