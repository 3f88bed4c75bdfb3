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

#include "droplet_model.hpp"
#include "droplet_runtime.hpp"
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
std::int64_t& test_seam::lane_constraint_groups() {
  thread_local std::int64_t groups = 0;
  return groups;
}
std::atomic<bool>& test_seam::ring_pruning() {
  static std::atomic<bool> on{true};
  return on;
}
std::int64_t& test_seam::ring_grid_edges() {
  thread_local std::int64_t edges = 0;
  return edges;
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

Simulation::Simulation(const DropletParams& params, const Medium& medium)
    : model_(std::make_shared<const DropletModel>(params, medium)), runtime_(std::make_unique<DropletRuntime>()) {
  // The grains or the image's solid parts, and a last entry for none (contact.touch's).
  runtime_->touched.assign(static_cast<std::size_t>(model_->obstacles) + 1, 0);
  place(0.5 * medium.width, model_->start_y);
}

Simulation::Simulation(const Simulation& other)
    : model_(other.model_), runtime_(std::make_unique<DropletRuntime>(*other.runtime_)) {}

Simulation& Simulation::operator=(const Simulation& other) {
  if (this != &other) {
    model_ = other.model_;
    runtime_ = std::make_unique<DropletRuntime>(*other.runtime_);
  }
  return *this;
}

Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

void Simulation::place(double cx, double cy) {
  const DropletParams& p = model_->params;
  DropletRuntime& r = *runtime_;
  DropletState& state = r.state;
  r.changed();
  place_droplet(p, cx, cy, &state);
  // Start at rest at t = 0: x(-dt) = x(0) + g dt^2 / 2 makes Verlet exact for free fall.
  for (int i = 0; i < state.size(); ++i) state.py[i] += 0.5 * p.gravity * p.dt * p.dt;
  std::fill(r.touched.begin(), r.touched.end(), 0);
  r.spring_force.assign(4 * state.x.size(), 0.0);  // so that step() allocates nothing
  // A point is rarely inside more than a few discs; a mass inside more than this is looked up
  // again by the collisions. (A cell's full count could be thousands in a coarse grid.)
  r.contact.reset(state.x.size(), std::min<std::size_t>(model_->grid.max_cell_entries(), 8), model_->obstacles);
  r.area = ring_area(state);
  r.last_penetration = 0;
}

void Simulation::place_above(double cx) { place(cx, model_->start_y); }

const DropletState& Simulation::state() const { return runtime_->state; }
DropletState& Simulation::mutable_state() {
  runtime_->changed();
  return runtime_->state;
}
const DropletParams& Simulation::params() const { return model_->params; }
const Medium& Simulation::medium() const { return model_->medium; }
double Simulation::area() const { return runtime_->area; }
double Simulation::initial_area() const { return model_->area0; }
double Simulation::last_penetration() const { return runtime_->last_penetration; }
double Simulation::start_height() const { return model_->start_y; }

void Simulation::centre_of_mass(double* cx, double* cy) const {
  // The lane-by-lane block's sum where its step left the state as it is (the same kernel at eight
  // lanes: the same bits); every other writer of the state clears the block id.
  if (const BlockSlot& slot = runtime_->block; slot.id != 0 && slot.id == slot.centre_id) {
    *cx = slot.cx;
    *cy = slot.cy;
    return;
  }
  const DropletState& state = runtime_->state;
  lanes::scalar::centres_k<1>(state.x.data(), state.y.data(), state.size(), cx, cy);
}

const char* to_string(StepStage stage) {
  static constexpr const char* kNames[] = {"gravity",    "springs",       "pressure",  "vibration",
                                           "collisions", "ring_contacts", "viscosity", "integrate",
                                           "constraint", "contact_limit", "ring_limit"};
  static_assert(std::size(kNames) == kStepStages.size());
  const auto i = static_cast<std::size_t>(stage);
  return i < std::size(kNames) ? kNames[i] : "?";
}

void Simulation::compute_forces() {
  OneRing ring(*this);
  run_stages(ring, StepStage::gravity, StepStage::viscosity);
}

bool Simulation::step() {
  OneRing ring(*this);
  run_stages(ring);
  return runtime_->valid();
}

// ---- Checks and the run loop ------------------------------------------------------------------

bool any_grain_inside_ring(const DropletState& state, const Medium& medium) {
  const int n = state.size();
  double x0 = state.x[0], x1 = x0, y0 = state.y[0], y1 = y0;
  for (int i = 1; i < n; ++i) {
    x0 = std::min(x0, state.x[i]);
    x1 = std::max(x1, state.x[i]);
    y0 = std::min(y0, state.y[i]);
    y1 = std::max(y1, state.y[i]);
  }
  const double W = medium.width;
  for (const Grain& g : medium.grains) {
    if (g.y < y0 || g.y > y1) continue;
    // The ring is unwrapped; try the grain's periodic copies that can fall in its x range.
    double gx = g.x;
    if (medium.periodic) gx += W * std::floor((x0 - g.x) / W);
    for (; gx <= x1; gx += W) {
      if (gx >= x0 && ring_contains(state, gx, g.y)) return true;
      if (!medium.periodic) break;
    }
  }
  return false;
}

namespace {
// Steps sim to an outcome; placed as RunStepper's (the x the ring was just placed at, or null).
RunSummary drive(Simulation* sim, const RunOptions& options, const double* placed) {
  RunStepper run(sim, options, placed);
  while (!run.finished()) run.after_step(sim->step());
  return run.take();
}
}  // namespace

RunSummary Simulation::run(double cx, const RunOptions& options) {
  place_above(cx);
  return drive(this, options, &cx);
}

RunSummary Simulation::run_from_current(const RunOptions& options) { return drive(this, options, nullptr); }

bool Simulation::valid() const { return runtime_->valid(); }

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
  const DropletState& state = runtime_->state;
  mix(state.x);
  mix(state.y);
  mix(state.px);
  mix(state.py);
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
