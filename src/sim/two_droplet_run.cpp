// Two droplets one after the other (simulation.hpp): the release rule, the pair's step through
// the driver (a RingGroup of the two rings) and the two runs' book-keeping.
#include "two_droplet_run.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "ring_group_step.hpp"
#include "util/enum_names.hpp"
#include "util/validation.hpp"

namespace softdrop {

constexpr detail::EnumName<SecondRelease> kSecondReleases[] = {{SecondRelease::distance, "distance"},
                                                               {SecondRelease::delay, "delay"}};

const char* to_string(SecondRelease release) { return detail::name_of(kSecondReleases, release); }

SecondRelease parse_second_release(const std::string& name) {
  return detail::parse_name(kSecondReleases, name, "second-droplet");
}

bool SecondDroplet::IsValid(const DropletParams& droplet, std::string* why) const {
  using detail::fail;
  using detail::num;
  if (!std::isfinite(after) || after <= 0) return fail(why, "second-after = " + num(after) + ": must be > 0");
  if (!std::isfinite(offset_x)) return fail(why, "second-offset-x = " + num(offset_x) + ": must be finite");
  // Two rings within their circumradius R each, and the contact's reach between them.
  const double apart = 2 * droplet.radius + droplet.max_depth;
  if (std::abs(offset_x) >= apart) return true;
  if (release == SecondRelease::distance && after < apart)
    return fail(why, "second-after = " + num(after) +
                         ": the second droplet would start overlapping the first; the first must be at least 2 R + "
                         "max-depth = " +
                         num(apart) + " below its start (or the starts that far apart, second-offset-x)");
  if (release == SecondRelease::delay && 0.5 * std::abs(droplet.gravity) * after * after < apart)
    return fail(why, "second-after = " + num(after) +
                         ": the second droplet would start overlapping the first; in that delay free fall covers " +
                         num(0.5 * std::abs(droplet.gravity) * after * after) + " < 2 R + max-depth = " + num(apart));
  return true;
}

TwoDropletRun::TwoDropletRun(const DropletParams& droplet, const Medium& medium, double x0, const RunOptions& options,
                             const SecondDroplet& second)
    : first_(droplet, medium),
      second_(first_),
      options_(options),
      rule_(second),
      x0_(x0),
      x1_(x0 + second.offset_x),
      released_at_(std::numeric_limits<double>::quiet_NaN()) {
  std::string why;
  if (!second.IsValid(droplet, &why)) throw std::invalid_argument(why);
  if (!medium.periodic && (x1_ < droplet.radius || x1_ > medium.width - droplet.radius))
    throw std::invalid_argument("second-offset-x = " + detail::num(second.offset_x) +
                                ": the second droplet's start x = " + detail::num(x1_) +
                                " is not within the walls, [R, W - R]");
  first_.place_above(x0_);
  second_.place_above(x1_);
  first_run_.emplace(&first_, options_, &x0_);
  share_shaking();
}

void TwoDropletRun::share_shaking() {
  RunStepper* runs[2] = {&*first_run_, second_run_ ? &*second_run_ : nullptr};
  if (shaken_from_ < 0)
    for (const RunStepper* r : runs)
      if (r && r->shaking()) shaken_from_ = k_ - r->shaking_for();  // it began the shaking
  if (shaken_from_ < 0) return;
  for (RunStepper* r : runs)
    if (r && !r->finished() && (!r->shaking() || r->shaking_for() != k_ - shaken_from_))
      r->join_shaking(k_ - shaken_from_);
}

void TwoDropletRun::begin_step(Simulation** a, Simulation** b) {
  RunStepper& first = *first_run_;
  a_on_ = !first.finished();
  b_on_ = second_running();
  // A droplet found stuck is held while the other may still move it: before the release (once:
  // the release follows), and while the other runs and is not held itself.
  if (a_on_) first.hold_when_stuck(second_run_ ? b_on_ && !second_run_->held() : !first.held());
  if (b_on_) second_run_->hold_when_stuck(a_on_ && !first.held());
  *a = a_on_ ? &first_ : nullptr;
  *b = b_on_ ? &second_ : nullptr;
}

void TwoDropletRun::step() {
  Simulation *a = nullptr, *b = nullptr;
  begin_step(&a, &b);
  Simulation* sims[2] = {a ? a : b, b};
  RingPair pair{0, 1, &scratch_, 0};
  RingGroup rings{sims, a && b ? 2 : 1, &group_rings_, &group_corrections_, &pair, a && b ? 1 : 0};
  run_stages(rings);
  end_step(pair.moved);
}

void TwoDropletRun::end_step(int moved) {
  limited_ = moved;
  if (a_on_ && b_on_ && scratch_.contacts > 0) ++contact_steps_;
  ++k_;
  if (a_on_) first_run_->after_step(first_.runtime().valid());
  if (b_on_) second_run_->after_step(second_.runtime().valid());
  if (!second_run_) release_if_due();
  share_shaking();
}

void TwoDropletRun::release_if_due() {
  const RunStepper& a = *first_run_;
  const double dt = first_.params().dt;
  const bool due = a.finished() || a.held() ||
                   (rule_.release == SecondRelease::distance ? first_.start_height() - a.centre_y() >= rule_.after
                                                             : static_cast<double>(k_) * dt >= rule_.after);
  if (!due) return;
  // A first droplet that left the medium is out of reach; one that is still in the box must be
  // clear of the second's start.
  if (!a.finished() || a.centre_y() >= 0) {
    if (rings_within(first_.state(), second_.state(), first_.medium(), first_.params().max_depth)) return;
  }
  second_run_.emplace(&second_, options_, &x1_);
  released_at_ = static_cast<double>(k_) * dt;
}

TwoDropletSummary TwoDropletRun::take() {
  TwoDropletSummary s;
  s.first_held_at = first_run_->held_at();
  s.first = first_run_->take();
  s.released = second_run_.has_value();
  s.released_at = released_at_;
  if (second_run_) {
    s.second_held_at = second_run_->held_at();
    s.second = second_run_->take();
  } else {
    s.second.outcome = Outcome::timeout;
    s.second.reason = "never released: the first droplet's run ended within reach of the second's start";
    s.second.start_x = x1_;
    s.second.start_y = first_.start_height();
  }
  s.contact_steps = contact_steps_;
  std::vector<std::int32_t> both;
  std::set_intersection(s.first.touched.begin(), s.first.touched.end(), s.second.touched.begin(),
                        s.second.touched.end(), std::back_inserter(both));
  s.shared_touched = static_cast<int>(both.size());
  return s;
}

TwoDropletSummary run_two_droplets(const DropletParams& droplet, const Medium& medium, double x0,
                                   const RunOptions& options, const SecondDroplet& second) {
  TwoDropletRun run(droplet, medium, x0, options, second);
  while (!run.finished()) run.step();
  return run.take();
}

}  // namespace softdrop
