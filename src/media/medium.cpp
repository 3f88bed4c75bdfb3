#include "softdrop/medium.hpp"

#include <cmath>
#include <stdexcept>

#include "media/image_medium.hpp"
#include "media/relaxation.hpp"
#include "spacing.hpp"
#include "util/enum_names.hpp"
#include "util/random.hpp"
#include "util/validation.hpp"

namespace softdrop {
using detail::fail;
using detail::num;

namespace {
// The box's sides, as Medium and MediumOptions both check them.
bool box_is_valid(double width, double height, std::string* why) {
  if (!(width > 0 && width <= kMaxBoxSide)) return fail(why, "width = " + num(width) + ": must be in (0, 1e9]");
  if (!(height > 0 && height <= kMaxBoxSide)) return fail(why, "height = " + num(height) + ": must be in (0, 1e9]");
  return true;
}
}  // namespace

bool Medium::IsValid(std::string* why) const {
  if (!box_is_valid(width, height, why)) return false;
  if (image) return detail::image_is_valid(*this, why);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const Grain& g = grains[i];
    const std::string at = "grain " + std::to_string(i) + ": ";
    if (!std::isfinite(g.x) || !std::isfinite(g.y)) return fail(why, at + "non-finite centre");
    if (!std::isfinite(g.r) || g.r <= 0) return fail(why, at + "radius " + num(g.r) + " must be > 0");
    if (periodic && 2 * g.r >= width) return fail(why, at + "diameter must be smaller than width");
    // Periodic images are made across one seam only, so a centre must lie in the box's x range.
    if (periodic && !(g.x >= 0 && g.x <= width))
      return fail(why, at + "centre x = " + num(g.x) + " must be in [0, width] in a periodic medium");
    // A grain must reach into the box: one wholly above it would sit on the droplet's start, one
    // wholly below it would count for nothing.
    if (!(g.y > -g.r && g.y < height + g.r))
      return fail(why, at + "centre y = " + num(g.y) + " with radius " + num(g.r) +
                           " lies wholly outside the box in y (y must be in (-r, height + r))");
  }
  return true;
}

constexpr detail::EnumName<MediumKind> kMediumKinds[] = {{MediumKind::overlapping, "overlapping"},
                                                         {MediumKind::non_overlapping, "non-overlapping"},
                                                         {MediumKind::relaxed, "relaxed"}};
constexpr detail::EnumName<RadiusDistribution> kRadiusDistributions[] = {{RadiusDistribution::uniform, "uniform"},
                                                                         {RadiusDistribution::lognormal, "lognormal"}};

MediumKind parse_medium_kind(const std::string& name) {
  if (name == "nonoverlapping") return MediumKind::non_overlapping;  // also taken, not offered
  return detail::parse_name(kMediumKinds, name, "kind");
}

RadiusDistribution parse_radius_distribution(const std::string& name) {
  return detail::parse_name(kRadiusDistributions, name, "radius-distribution");
}

const char* to_string(MediumKind kind) { return detail::name_of(kMediumKinds, kind); }

const char* to_string(RadiusDistribution radii) { return detail::name_of(kRadiusDistributions, radii); }

std::vector<std::string> medium_kind_names() { return detail::name_list(kMediumKinds); }

std::vector<std::string> radius_distribution_names() { return detail::name_list(kRadiusDistributions); }

namespace {
double mean_disc_area(const MediumOptions& o);
}  // namespace

bool MediumOptions::IsValid(std::string* why) const {
  if (!std::isfinite(porosity) || porosity <= 0 || porosity >= 1)
    return fail(why, "porosity = " + num(porosity) + ": must be in (0, 1)");
  if (grains < 0 || grains > 10'000'000)
    return fail(why, "grains = " + std::to_string(grains) + ": must be in [0, 1e7]");
  if (!box_is_valid(width, height, why)) return false;
  if (!std::isfinite(r_min) || r_min <= 0) return fail(why, "r-min = " + num(r_min) + ": must be > 0");
  if (!std::isfinite(r_max) || r_max < r_min) return fail(why, "r-max = " + num(r_max) + ": must be >= r-min");
  if (2 * r_max >= width) return fail(why, "r-max = " + num(r_max) + ": diameter must be < width");
  // Also for overlapping media: in a box lower than a grain, discs are mostly cut off and the
  // grain count needed for a porosity target has no useful bound.
  if (2 * r_max > height) return fail(why, "r-max = " + num(r_max) + ": diameter must be <= height");
  if (radii == RadiusDistribution::lognormal) {
    if (!std::isfinite(r_median) || r_median < r_min || r_median > r_max)
      return fail(why, "r-median = " + num(r_median) + ": must be in [r-min, r-max]");
    if (!std::isfinite(r_sigma) || r_sigma <= 0 || r_sigma > 5)
      return fail(why, "r-sigma = " + num(r_sigma) + ": must be in (0, 5]");
  }
  if (!std::isfinite(gap) || gap < 0) return fail(why, "gap = " + num(gap) + ": must be >= 0");
  if (max_failed_attempts <= 0)
    return fail(why, "max-failed-attempts = " + std::to_string(max_failed_attempts) + ": must be > 0");
  // Non-overlapping grains of radius >= r_min, kept gap * r_min apart and inside the box in y,
  // are disjoint once each is grown by gap * r_min / 2: their area cannot exceed the (grown) box's.
  if (kind != MediumKind::overlapping && grains > 0) {
    const double grown = r_min * (1 + 0.5 * gap);
    const double room = width * (height + gap * r_min) / (M_PI * grown * grown);
    if (grains > room)
      return fail(why, "grains = " + std::to_string(grains) + ": cannot fit in " + num(width) + " x " + num(height) +
                           ": even the smallest grains (radius " + num(r_min) + ", gap " + num(gap) +
                           ") would need more than the box's area; at most " + num(std::floor(room)));
  }
  // Refuse a porosity target that needs more grains than any medium may hold, before allocating.
  if (grains == 0) {
    const double solid = kind == MediumKind::overlapping ? -std::log(porosity) : 1 - porosity;
    const double expected = solid * width * height / mean_disc_area(*this);
    if (!(expected <= 1e7))
      return fail(why, "width = " + num(width) + ", height = " + num(height) + ": porosity " + num(porosity) +
                           " needs about " + num(std::round(expected)) + " grains, more than the limit of 1e7");
  }
  return true;
}

namespace {

// Standard normal deviate by Box-Muller from two portable uniforms.
double standard_normal(Rng& rng) {
  const double u = 1.0 - rng.uniform();  // (0, 1]
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2 * M_PI * rng.uniform());
}

double random_radius(Rng& rng, const MediumOptions& o) {
  if (o.r_min == o.r_max) return o.r_min;
  if (o.radii == RadiusDistribution::uniform) return rng.uniform(o.r_min, o.r_max);
  for (;;) {  // truncated log-normal; the median lies inside, so acceptance is at least ~50 %
    const double r = o.r_median * std::exp(o.r_sigma * standard_normal(rng));
    if (r >= o.r_min && r <= o.r_max) return r;
  }
}

// Mean disc area of the radius distribution (for the first guess of the grain count).
double mean_disc_area(const MediumOptions& o) {
  if (o.radii == RadiusDistribution::uniform)
    return M_PI * (o.r_min * o.r_min + o.r_min * o.r_max + o.r_max * o.r_max) / 3;
  return M_PI * o.r_median * o.r_median * std::exp(2 * o.r_sigma * o.r_sigma);
}

Grain random_grain(Rng& rng, const MediumOptions& o) {
  Grain g;
  g.r = random_radius(rng, o);
  if (o.kind == MediumKind::overlapping) {
    g.x = rng.uniform(0, o.width);
    g.y = rng.uniform(0, o.height);
  } else {
    g.x = o.periodic ? rng.uniform(0, o.width) : rng.uniform(g.r, o.width - g.r);
    g.y = rng.uniform(g.r, o.height - g.r);
  }
  return g;
}

Medium overlapping_medium(const MediumOptions& o) {
  // The porosity of a prefix of a fixed random sequence of discs falls monotonically with its
  // length, so the smallest prefix reaching the target is found by bisection over exact porosities.
  Rng rng(derive_seed(o.seed, 0));
  Medium m{o.width, o.height, o.periodic, {}, nullptr};
  if (o.grains > 0) {
    for (int i = 0; i < o.grains; ++i) m.grains.push_back(random_grain(rng, o));
    return m;
  }
  const double expected = -std::log(o.porosity) * o.width * o.height / mean_disc_area(o);
  std::vector<Grain> pool;
  auto porosity_of = [&](std::size_t n) {
    Medium prefix{o.width, o.height, o.periodic,
                  std::vector<Grain>(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(n)), nullptr};
    return exact_porosity(prefix);
  };
  std::size_t hi = static_cast<std::size_t>(1.3 * expected) + 16;
  constexpr std::size_t kMaxGrains = 40'000'000;  // 4x the limit IsValid puts on the expected count
  for (;;) {
    while (pool.size() < hi) pool.push_back(random_grain(rng, o));
    if (porosity_of(hi) <= o.porosity) break;
    if (hi > kMaxGrains)
      throw std::runtime_error("porosity = " + num(o.porosity) + ": not reached with " + std::to_string(hi) +
                               " grains");
    hi *= 2;
  }
  std::size_t lo = 0;  // porosity_of(lo) > target (lo = 0 has porosity 1)
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (porosity_of(mid) <= o.porosity ? hi : lo) = mid;
  }
  m.grains.assign(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(hi));
  return m;
}

// Whether disjoint grains inside the box, `count` of them covering `solid`, are still short of
// the options' target: the grain count, or else the porosity 1 - solid / box.
bool short_of_target(const MediumOptions& o, std::size_t count, double solid) {
  return o.grains > 0 ? count < static_cast<std::size_t>(o.grains) : 1 - solid / (o.width * o.height) > o.porosity;
}

Medium non_overlapping_medium(const MediumOptions& o) {
  Rng rng(derive_seed(o.seed, 1));
  Medium m{o.width, o.height, o.periodic, {}, nullptr};
  SpacingIndex index(o.width, o.height, o.periodic, o.gap, o.r_max);
  // Grains lie inside the box in y and do not overlap, so the solid area is the sum of disc areas.
  const double box = o.width * o.height;
  double solid = 0;
  int failed = 0;
  while (short_of_target(o, m.grains.size(), solid)) {
    const Grain g = random_grain(rng, o);
    if (!index.can_place(g)) {
      if (++failed >= o.max_failed_attempts && o.grains > 0)
        throw std::runtime_error("grains = " + std::to_string(o.grains) + ": do not fit in the box with gap " +
                                 num(o.gap) + " (jammed after " + std::to_string(m.grains.size()) + " grains)");
      if (failed >= o.max_failed_attempts)
        throw std::runtime_error(
            "porosity = " + num(o.porosity) + ": unreachable for non-overlapping grains with gap " + num(o.gap) +
            " (jammed at porosity " + num(1 - solid / box) + " with " + std::to_string(m.grains.size()) + " grains)");
      continue;
    }
    failed = 0;
    index.insert(g);
    m.grains.push_back(g);
    solid += M_PI * g.r * g.r;
  }
  return m;
}

// Passes of relaxation before the grains are declared too many for the box: a bound on the work
// of a target that cannot be reached (in the default box 20 000 passes take about 0.2 s).
constexpr int kMaxRelaxationSweeps = 20000;

Medium relaxed_medium(const MediumOptions& o) {
  Rng rng(derive_seed(o.seed, 2));
  Medium m{o.width, o.height, o.periodic, {}, nullptr};
  const double box = o.width * o.height;
  double solid = 0;
  while (short_of_target(o, m.grains.size(), solid)) {
    m.grains.push_back(random_grain(rng, o));
    solid += M_PI * m.grains.back().r * m.grains.back().r;
  }
  // A porosity target keeps the grain count whose porosity is nearest to it (one grain of radius
  // 48 is 3 % of the default box), the last grain or not.
  if (o.grains == 0 && m.grains.size() > 1) {
    const double last = M_PI * m.grains.back().r * m.grains.back().r;
    if (std::abs(1 - (solid - last) / box - o.porosity) < std::abs(1 - solid / box - o.porosity)) m.grains.pop_back();
  }
  if (!detail::relax_spacing(m.grains, o.width, o.height, o.periodic, o.gap, kMaxRelaxationSweeps))
    throw std::runtime_error((o.grains > 0 ? "grains = " + std::to_string(o.grains) : "porosity = " + num(o.porosity)) +
                             ": unreachable for relaxed grains with gap " + num(o.gap) + " (" +
                             std::to_string(m.grains.size()) + " grains, some still too close after " +
                             std::to_string(kMaxRelaxationSweeps) + " passes of relaxation)");
  return m;
}

}  // namespace

Medium generate_medium(const MediumOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  switch (options.kind) {
    case MediumKind::overlapping:
      return overlapping_medium(options);
    case MediumKind::non_overlapping:
      return non_overlapping_medium(options);
    case MediumKind::relaxed:
      break;
  }
  return relaxed_medium(options);
}

}  // namespace softdrop
