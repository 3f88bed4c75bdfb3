#pragma once
// RunStepper: one droplet's run between its steps (path, recordings, exit tests), shared by the
// one-droplet loop (Simulation::run_from_current) and the interleaved scheduler.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "droplet_model.hpp"
#include "droplet_runtime.hpp"
#include "softdrop/simulation.hpp"
#include "step_helpers.hpp"

namespace softdrop {

/// Whether a grain's centre (or, in a periodic medium, a periodic copy's) is inside the ring.
bool any_grain_inside_ring(const DropletState& state, const Medium& medium);

// One droplet's run between its steps: the path, the recordings and the exit tests. A driver
// steps the simulation and calls after_step(); run_from_current drives one droplet,
// run_interleaved several.
class RunStepper {
 public:
  /// placed: the droplet was just placed above the medium at x = *placed (place_above), which the
  /// summary reports as its start, so that running from there again gives the same bits; null: the
  /// run goes on from another state, and its start is the centre of mass.
  RunStepper(Simulation* sim, const RunOptions& options, const double* placed = nullptr)
      : sim_(sim), m_(sim->model()), r_(sim->runtime()), o_(options) {
    std::string why;
    if (!options.IsValid(&why)) throw std::invalid_argument(why);
    dt_ = m_.params.dt;
    H_ = m_.medium.height;
    sim->centre_of_mass(&cx_, &cy_);
    s_.start_x = placed ? *placed : cx_;
    s_.start_y = placed ? m_.start_y : cy_;
    r_.area = ring_area(r_.state);
    window_ = std::max<std::int64_t>(1, std::llround(options.stuck_window / dt_));
    rest_window_ = options.rest_window > 0 ? std::max<std::int64_t>(1, std::llround(options.rest_window / dt_)) : 0;
    for (double t : options.snapshot_times) snapshot_steps_.push_back(std::llround(t / dt_));
    std::sort(snapshot_steps_.begin(), snapshot_steps_.end());
    record(0);
    path_.entered = cy_ < H_;
    checkpoint_y_ = cy_;
    next_stuck_check_ = window_;
    r_.shake.on = false;
    if (m_.params.vibrates() && m_.params.vibration_start == VibrationStart::start) start_shaking(0);
  }

  bool finished() const { return finished_; }
  Simulation* simulation() const { return sim_; }
  /// The centre of mass's y after the last step (length).
  double centre_y() const { return cy_; }
  /// Holds the droplet (or not) at its next stuck or rest verdict: a held droplet is not ended
  /// there, its stuck test starts a new window, and held() is true until a window shows descent.
  /// Two droplets hold each other so while the other still moves, which may free it.
  void hold_when_stuck(bool hold) { hold_ = hold; }
  bool held() const { return held_; }
  /// When the droplet was first held, in time units since its run began; NaN if never.
  double held_at() const { return held_at_; }
  /// Whether the medium shakes for this droplet, and for how many steps it has (by its clock).
  bool shaking() const { return shaking_; }
  std::int64_t shaking_for() const { return k_ - shaking_from_; }
  /// From the next step, the medium shakes for this droplet as one that has shaken for `steps`
  /// steps already: two droplets in one medium share its clock. A droplet that was not shaking
  /// begins to (its shaken_at is now, its stuck window starts again); one that was keeps its
  /// route and takes the medium's phase.
  void join_shaking(std::int64_t steps) {
    if (finished_) return;
    if (!shaking_) start_shaking(k_);
    shaking_from_ = k_ - steps;
    shake_for_step(k_);
  }

  /// Book-keeping of the step just taken (ok: the step's own validity test); may end the run.
  void after_step(bool ok) {
    const std::int64_t k = ++k_;
    const double pcx = cx_, pcy = cy_;
    sim_->centre_of_mass(&cx_, &cy_);
    if (!ok || !std::isfinite(cx_) || !std::isfinite(cy_)) {
      std::ostringstream r;
      r << "ring became invalid at step " << k << " (area " << r_.area << ")";
      return finish(Outcome::diverged, r.str(), k);
    }
    s_.min_area_ratio = std::min(s_.min_area_ratio, r_.area / m_.area0);
    s_.max_penetration = std::max(s_.max_penetration, r_.last_penetration);
    // The step's travel, for the path and the rest test alike.
    const double travel = step_detail::distance(pcx, pcy, cx_, cy_);
    path_.add(pcx, pcy, cx_, cy_, H_, travel);
    if (shaking_ && (cy_ < 0 || static_cast<double>(k - shaking_from_) * dt_ * m_.params.vibration_frequency >=
                                    static_cast<double>(periods_))) {
      // The route: the centre once a shaking period (at the first step of each), and where it left.
      route_.add(route_x_, route_y_, cx_, cy_, H_);
      route_x_ = cx_, route_y_ = cy_;
      ++periods_;
    }
    record(k);
    if (cy_ < 0) {
      s_.tortuosity = path_.length / H_;
      s_.route_tortuosity = shaking_ ? route_.length / H_ : s_.tortuosity;
      return finish(Outcome::passed, "centre of mass left the medium at y = 0", k);
    }
    if (k % o_.check_interval == 0) {
      if (o_.cancelled && o_.cancelled()) throw RunCancelled{};
      if (ring_self_intersects(r_.state))
        return finish(Outcome::diverged, "ring self-intersects at step " + std::to_string(k), k);
      if (any_grain_inside_ring(r_.state, m_.medium)) {
        s_.grain_inside_ring = true;
        return finish(Outcome::diverged, "a grain got inside the ring at step " + std::to_string(k), k);
      }
    }
    if (k == next_stuck_check_) {
      next_stuck_check_ += window_;
      if (checkpoint_y_ - cy_ < o_.stuck_distance) {
        if (shaking_pending()) return start_shaking(k);
        if (hold_) return hold(k);
        std::ostringstream r;
        r << "centre of mass moved down " << checkpoint_y_ - cy_ << " < " << o_.stuck_distance << " in the last "
          << o_.stuck_window << " time units, at y = " << cy_ << (shaking_ ? " while the medium shook" : "");
        return finish(Outcome::stuck, r.str(), k);
      }
      checkpoint_y_ = cy_;
      held_ = false;
    }
    // While the medium shakes, the droplet's travel is mostly the shaking's: the stuck test alone
    // judges its progress.
    if (rest_window_ > 0 && !shaking_) {
      // The centre's travel in any direction: a droplet bouncing off a grain travels far while
      // making no net progress, and is not at rest.
      rest_travel_ += travel;
      if (k % rest_window_ == 0) {
        if (rest_travel_ < o_.rest_distance) {
          if (shaking_pending()) return start_shaking(k);
          if (hold_) {
            rest_travel_ = 0;
            return hold(k);
          }
          std::ostringstream r;
          r << "at rest: centre of mass travelled " << rest_travel_ << " < " << o_.rest_distance << " in the last "
            << o_.rest_window << " time units, at y = " << cy_;
          return finish(Outcome::stuck, r.str(), k);
        }
        rest_travel_ = 0;
      }
    }
    if (k >= o_.max_steps)  // (>=: a step that starts the shaking skips this test)
      return finish(Outcome::timeout, "step budget of " + std::to_string(o_.max_steps) + " steps spent", k);
    if (shaking_) shake_for_step(k);
  }

  RunSummary take() { return std::move(s_); }

 private:
  void record(std::int64_t k) {
    const double t = static_cast<double>(k) * dt_;
    if (o_.path_interval > 0 && k % o_.path_interval == 0) {
      s_.path_t.push_back(t);
      s_.path_x.push_back(cx_);
      s_.path_y.push_back(cy_);
    }
    if (o_.area_interval > 0 && k % o_.area_interval == 0) {
      s_.area_t.push_back(t);
      s_.area.push_back(ring_area(r_.state));
    }
    while (next_snapshot_ < snapshot_steps_.size() && snapshot_steps_[next_snapshot_] <= k) {
      s_.snapshots.push_back({t, r_.state.x, r_.state.y});
      ++next_snapshot_;
    }
  }
  // The medium shakes from rest and has not begun to.
  bool shaking_pending() const {
    return !shaking_ && m_.params.vibrates() && m_.params.vibration_start == VibrationStart::rest;
  }
  // The medium begins to shake after step k: the stuck test's window starts again from here.
  void start_shaking(std::int64_t k) {
    shaking_ = true;
    shaking_from_ = k;
    s_.shaken_at = static_cast<double>(k) * dt_;
    route_ = path_;
    route_x_ = cx_, route_y_ = cy_;
    periods_ = 1;
    checkpoint_y_ = cy_;
    next_stuck_check_ = k + window_;
    shake_for_step(k);
  }
  // Not ended at a stuck or rest verdict after step k: the stuck test's window starts again.
  void hold(std::int64_t k) {
    if (std::isnan(held_at_)) held_at_ = static_cast<double>(k) * dt_;
    held_ = true;
    checkpoint_y_ = cy_;
    next_stuck_check_ = k + window_;
    if (k >= o_.max_steps)
      return finish(Outcome::timeout, "step budget of " + std::to_string(o_.max_steps) + " steps spent", k);
    if (shaking_) shake_for_step(k);
  }
  // The shaking's force for the step after step k, at the time that step begins.
  void shake_for_step(std::int64_t k) {
    r_.shake.set(m_.params, r_.state.size(), static_cast<double>(k - shaking_from_) * dt_);
  }
  void finish(Outcome o, std::string reason, std::int64_t k) {
    finished_ = true;
    s_.path_length = path_.length;
    r_.shake.on = false;  // steps after the run do not shake
    s_.outcome = o;
    s_.reason = std::move(reason);
    s_.steps = k;
    for (std::size_t g = 0; g + 1 < r_.touched.size(); ++g)
      if (r_.touched[g]) s_.touched.push_back(static_cast<std::int32_t>(g));
    if (o_.path_interval > 0 && (s_.path_t.empty() || s_.path_t.back() != static_cast<double>(k) * dt_)) {
      s_.path_t.push_back(static_cast<double>(k) * dt_);
      s_.path_x.push_back(cx_);
      s_.path_y.push_back(cy_);
    }
  }

  Simulation* sim_;
  const DropletModel& m_;  // the simulation's, read at every step without a call
  DropletRuntime& r_;
  const RunOptions& o_;
  RunSummary s_;
  double dt_ = 0, H_ = 0, cx_ = 0, cy_ = 0, checkpoint_y_ = 0, rest_travel_ = 0;
  std::int64_t window_ = 1, rest_window_ = 0, k_ = 0;
  std::int64_t next_stuck_check_ = 1, shaking_from_ = 0;  // the stuck test's next step; the shaking's first
  bool shaking_ = false;
  bool hold_ = false, held_ = false;
  double held_at_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::int64_t> snapshot_steps_;
  std::size_t next_snapshot_ = 0;
  bool finished_ = false;
  step_detail::PathInMedium path_;  // the centre's path, every step
  // From the shaking's start, the route: the path sampled once a shaking period.
  step_detail::PathInMedium route_;
  double route_x_ = 0, route_y_ = 0;
  std::int64_t periods_ = 1;
};

}  // namespace softdrop
