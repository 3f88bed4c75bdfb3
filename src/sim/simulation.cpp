// Simulation: creation, placement, the step as its list of stages (the force stages are in
// force_stages.cpp, the contact limit in contact_limit.cpp), the checks and the one-droplet run.
#include "softdrop/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "lane_scalar.hpp"
#include "run_stepper.hpp"
#include "step_context.hpp"
#include "step_driver.hpp"
#include "step_helpers.hpp"
#include "util/enum_names.hpp"
#include "util/validation.hpp"

namespace softdrop {

#if defined(SOFTDROP_TEST_HOOKS)
std::atomic<test_seam::StepMutation>& test_seam::step_mutation() {
  static std::atomic<StepMutation> mutation{StepMutation::none};
  return mutation;
}
#endif

constexpr detail::EnumName<Outcome> kOutcomes[] = {{Outcome::passed, "passed"},
                                                   {Outcome::stuck, "stuck"},
                                                   {Outcome::timeout, "timeout"},
                                                   {Outcome::diverged, "diverged"}};

const char* to_string(Outcome outcome) { return detail::name_of(kOutcomes, outcome); }

Outcome parse_outcome(const std::string& name) { return detail::parse_name(kOutcomes, name, "outcome"); }

bool RunOptions::IsValid(std::string* why) const {
  using detail::fail;
  using detail::num;
  if (max_steps <= 0) return fail(why, "max-steps = " + std::to_string(max_steps) + ": must be > 0");
  if (!std::isfinite(stuck_window) || stuck_window <= 0)
    return fail(why, "stuck-window = " + num(stuck_window) + ": must be > 0");
  if (!std::isfinite(stuck_distance) || stuck_distance < 0)
    return fail(why, "stuck-distance = " + num(stuck_distance) + ": must be >= 0");
  if (!std::isfinite(rest_window) || rest_window < 0)
    return fail(why, "rest-window = " + num(rest_window) + ": must be >= 0 (0: no rest test)");
  if (!std::isfinite(rest_distance) || rest_distance < 0)
    return fail(why, "rest-distance = " + num(rest_distance) + ": must be >= 0");
  if (check_interval <= 0) return fail(why, "check-interval = " + std::to_string(check_interval) + ": must be > 0");
  if (path_interval < 0) return fail(why, "path-interval = " + std::to_string(path_interval) + ": must be >= 0");
  if (area_interval < 0) return fail(why, "trace-interval = " + std::to_string(area_interval) + ": must be >= 0");
  for (double t : snapshot_times)
    if (!std::isfinite(t) || t < 0) return fail(why, "snapshot-times: " + num(t) + " must be finite and >= 0");
  return true;
}

namespace {
// The contact grid's halo, in cells: a mass's anchor ball (apply_contact_limit) may reach past its
// cell's edge by this much, so a mass moving through open pore space leaves its ball, and is
// tested against its whole cell, less often; a cell lists more discs (bench/README.md, "Constants
// of the step").
constexpr double kContactGridHalo = 0.5;
}  // namespace

Simulation::Simulation(const DropletParams& params, const Medium& medium)
    : params_(params), medium_(medium), grid_(medium, 0, kContactGridHalo) {
  std::string why;
  if (!params.IsValid(&why)) throw std::invalid_argument(why);
  if (!medium.IsValid(&why)) throw std::invalid_argument(why);
  context_ = std::make_shared<const StepContext>(make_step_context(params));
  area0_ = params.resting_area();
  // Only masses are tested against grains; a grain narrower than an edge could slip between two.
  const double longest_edge = context_->dmax;
  for (std::size_t i = 0; i < medium.grains.size(); ++i)
    if (medium.grains[i].r < longest_edge)
      throw std::invalid_argument("grain " + std::to_string(i) + " radius " + detail::num(medium.grains[i].r) +
                                  " is smaller than the droplet's longest edge " + detail::num(longest_edge) +
                                  ": use more masses, a smaller radius or larger grains");
  touched_.assign(medium.grains.size() + 1, 0);  // the last entry: no grain (contact_.touch's)
  double top = medium.height;
  for (const Grain& g : medium.grains) top = std::max(top, g.y + g.r);
  start_y_ = top + params.radius + 0.05 * params.radius;
  // Far above the rounding of any distance in the box (about 1e-15 of its size), far below any
  // distance that matters.
  contact_.clearance_margin = 1e-9 * (medium.width + start_y_);
  place(0.5 * medium.width, start_y_);
}

void Simulation::place(double cx, double cy) {
  state_changed();
  place_droplet(params_, cx, cy, &state_);
  // Start at rest at t = 0: x(-dt) = x(0) + g dt^2 / 2 makes Verlet exact for free fall.
  for (int i = 0; i < state_.size(); ++i) state_.py[i] += 0.5 * params_.gravity * params_.dt * params_.dt;
  std::fill(touched_.begin(), touched_.end(), 0);
  spring_force_.assign(4 * state_.x.size(), 0.0);  // so that step() allocates nothing
  // A point is rarely inside more than a few discs; a mass inside more than this is looked up
  // again by the collisions. (A cell's full count could be thousands in a coarse grid.)
  contact_.reset(state_.x.size(), std::min<std::size_t>(grid_.max_cell_entries(), 8),
                 static_cast<std::int32_t>(medium_.grains.size()));
  area_ = ring_area(state_);
  last_penetration_ = 0;
}

double Simulation::rest_length() const { return context_->rest_length; }

void Simulation::place_above(double cx) { place(cx, start_y_); }

void Simulation::centre_of_mass(double* cx, double* cy) const {
  lanes::scalar::centres_k<1>(state_.x.data(), state_.y.data(), state_.size(), cx, cy);
}

const char* to_string(StepStage stage) {
  static constexpr const char* kNames[] = {"gravity",   "springs",   "pressure",   "collisions",
                                           "viscosity", "integrate", "constraint", "contact_limit"};
  static_assert(std::size(kNames) == kStepStages.size());
  const auto i = static_cast<std::size_t>(stage);
  return i < std::size(kNames) ? kNames[i] : "?";
}

const StepContext& Simulation::step_context() const { return *context_; }

void Simulation::run_stage(StepStage stage) {
  OneRing ring{*this};
  run_stages(ring, stage, stage);
}

void Simulation::compute_forces() {
  OneRing ring{*this};
  run_stages(ring, StepStage::gravity, StepStage::viscosity);
}

void Simulation::apply_constraint() {
  state_changed();
  softdrop::apply_length_constraint(&state_, context_->rest_length, params_.max_strain, params_.constraint_iterations,
                                    params_.constraint_order);
}

bool Simulation::step() {
  OneRing ring{*this};
  run_stages(ring);
  return valid();
}

// ---- Checks and the run loop ------------------------------------------------------------------

bool Simulation::any_grain_inside_ring() const {
  const int n = state_.size();
  double x0 = state_.x[0], x1 = x0, y0 = state_.y[0], y1 = y0;
  for (int i = 1; i < n; ++i) {
    x0 = std::min(x0, state_.x[i]);
    x1 = std::max(x1, state_.x[i]);
    y0 = std::min(y0, state_.y[i]);
    y1 = std::max(y1, state_.y[i]);
  }
  const double W = medium_.width;
  for (const Grain& g : medium_.grains) {
    if (g.y < y0 || g.y > y1) continue;
    // The ring is unwrapped; try the grain's periodic copies that can fall in its x range.
    double gx = g.x;
    if (medium_.periodic) gx += W * std::floor((x0 - g.x) / W);
    for (; gx <= x1; gx += W) {
      if (gx >= x0 && ring_contains(state_, gx, g.y)) return true;
      if (!medium_.periodic) break;
    }
  }
  return false;
}

RunSummary Simulation::run(double cx, const RunOptions& options) {
  place_above(cx);
  return drive(options, &cx);
}

RunSummary Simulation::run_from_current(const RunOptions& options) { return drive(options, nullptr); }

RunSummary Simulation::drive(const RunOptions& options, const double* placed) {
  RunStepper run(this, options, placed);
  while (!run.finished()) run.after_step(step());
  return run.take();
}

bool Simulation::valid() const { return std::isfinite(area_) && area_ > 0; }

std::uint64_t Simulation::state_hash() const {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const std::vector<double>& v) {
    for (double d : v) {
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      for (int b = 0; b < 8; ++b) {
        h ^= (bits >> (8 * b)) & 0xFF;
        h *= 1099511628211ULL;
      }
    }
  };
  mix(state_.x);
  mix(state_.y);
  mix(state_.px);
  mix(state_.py);
  return h;
}

double polyline_tortuosity(const std::vector<double>& xs, const std::vector<double>& ys, double top) {
  double length = 0;
  bool entered = false;
  for (std::size_t k = 1; k < xs.size(); ++k) {
    const double ax = xs[k - 1], ay = ys[k - 1], bx = xs[k], by = ys[k];
    if (!entered) {
      if (ay >= top && by < top) {
        entered = true;
        const double f = (ay - top) / (ay - by);
        if (by < 0) {
          const double g = ay / (ay - by);
          return step_detail::distance(ax + f * (bx - ax), top, ax + g * (bx - ax), 0) / top;
        }
        length += step_detail::distance(ax + f * (bx - ax), top, bx, by);
      }
      continue;
    }
    if (by < 0) {
      const double f = ay / (ay - by);
      return (length + step_detail::distance(ax, ay, ax + f * (bx - ax), 0)) / top;
    }
    length += step_detail::distance(ax, ay, bx, by);
  }
  return 0;
}

}  // namespace softdrop
