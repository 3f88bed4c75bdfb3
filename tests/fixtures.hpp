#pragma once
// Shared scenes for the tests.

#include <cmath>
#include <set>
#include <string>

#include "balloon.hpp"
#include "sim/lane_policy.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"
#include "studies/calibration.hpp"
#include "util/random.hpp"

namespace softdrop::test {

/// The inflated ring of `masses` (default parameters otherwise) centred at (3, 4), every mass
/// moved by up to +-amplitude in x and y from stream `seed`: springs stretched and compressed.
inline DropletState jiggled_ring(int masses, std::uint64_t seed, double amplitude = 0.4) {
  DropletParams p;
  p.masses = masses;
  DropletState s;
  place_droplet(p, 3, 4, &s);
  Rng rng(seed);
  for (int i = 0; i < s.size(); ++i)
    s.x[i] += rng.uniform(-amplitude, amplitude), s.y[i] += rng.uniform(-amplitude, amplitude);
  return s;
}

/// The length of spring i of a ring: from mass i to the next (the last to the first).
inline double spring_length(const DropletState& s, int i) {
  const int j = (i + 1) % s.size();
  return std::hypot(s.x[j] - s.x[i], s.y[j] - s.y[i]);
}

/// Narrows the constraint's vector width for a scope (every width gives the same bits; tests
/// check that), then lets it use the widest the processor has again.
class VectorWidthLimit {
 public:
  explicit VectorWidthLimit(VectorWidth width) : in_use_(limit_constraint_vector_width(width)) {}
  ~VectorWidthLimit() { limit_constraint_vector_width(VectorWidth::avx512); }
  VectorWidthLimit(const VectorWidthLimit&) = delete;
  VectorWidthLimit& operator=(const VectorWidthLimit&) = delete;
  VectorWidth in_use() const { return in_use_; }

 private:
  VectorWidth in_use_;
};

/// The widths a test could not check because this processor lacks them. A test notes each width
/// as it tries it, checks the ones the processor has, and then skips with their names, so that a
/// run on a smaller processor does not pass as if it had checked every width.
class LackedWidths {
 public:
  /// Whether `limit` holds `width` (it clamps to what the processor has); notes it if not.
  bool has(const VectorWidthLimit& limit, VectorWidth width) {
    if (limit.in_use() == width) return true;
    lacked_.insert(static_cast<int>(width));
    return false;
  }
  bool any() const { return !lacked_.empty(); }
  /// "vector width 4, 8", for the skip message.
  std::string message() const {
    std::string m = "this processor lacks vector width";
    for (const int w : lacked_) m += (m.back() == 'h' ? " " : ", ") + std::to_string(w);
    return m + " (the widths it has were checked)";
  }

 private:
  std::set<int> lacked_;
};

/// Every vector width the constraint has.
inline constexpr VectorWidth kVectorWidths[] = {VectorWidth::scalar, VectorWidth::sse2, VectorWidth::avx,
                                                VectorWidth::avx512};

/// The balloon: the droplet the defaults were before the calibration
/// (results/calibration/balloon.toml), its gas holding every spring at the stretch limit. The
/// tests of the machinery (search, strategies, histories, stores) run it on their small scenes,
/// which were laid out for it: their histories do not depend on which droplet they run, and it
/// takes a sixth of the calibrated droplet's steps for the same time.
inline DropletParams balloon_droplet() { return DropletParams::balloon(); }
/// A calibration small enough for a unit test: porosities 0.7 and 0.9, 2 media of 200 x 200 each
/// with 3 droplets, and one trace medium with 2 droplets.
inline CalibrationOptions tiny_calibration() {
  CalibrationOptions o;
  o.sweep.porosities = {0.7, 0.9};
  o.sweep.media = 2;
  o.sweep.droplets = 3;
  o.sweep.medium.width = o.sweep.medium.height = 200;
  o.trace_media = 1;
  o.trace_droplets = 2;
  return o;
}
/// The two-droplet study's case, small: phi = 0.79, non-overlapping grains, 200 x 200.
inline Medium small_medium_079() {
  MediumOptions mo;
  mo.kind = MediumKind::non_overlapping;
  mo.porosity = 0.79;
  mo.width = mo.height = 200;
  mo.seed = 3;
  return generate_medium(mo);
}
/// The second droplet released soon after the first (the least descent that starts it clear of
/// the first), so that it catches up with it in the pores of small_medium_079.
inline SecondDroplet close_behind() {
  SecondDroplet second;
  const DropletParams p;
  second.after = 2 * p.radius + p.max_depth + 1;
  return second;
}
/// Run options with a step budget that lets both droplets of such a pair pass.
inline RunOptions long_enough() {
  RunOptions o;
  o.max_steps = 400000;
  return o;
}
/// An empty periodic box.
inline Medium empty_medium(double width = 500, double height = 500) { return Medium{width, height, true, {}, nullptr}; }

/// The paper's Fig. 2 scene: two grains whose gap (14) is narrower than the droplet's diameter
/// (20), and a third grain below the pore that the droplet must flow around.
inline Medium pore_of_three_grains() {
  Medium m{200, 200, true, {}, nullptr};
  const double r = 16, gap = 14;
  m.grains.push_back({100 - gap / 2 - r, 120, r});
  m.grains.push_back({100 + gap / 2 + r, 120, r});
  m.grains.push_back({112, 70, 14});
  return m;
}

/// A closed V: two overlapping grains (radius 30, centres 40 apart) whose tops stand 30 above
/// the notch between them, in a periodic box 200 wide with nothing else. A droplet dropped at
/// x = 100 comes to rest in the notch; shaken sideways at kVPocketAmplitude and 100 a time unit,
/// it climbs out and falls free.
inline Medium v_pocket() {
  Medium m{200, 120, true, {}, nullptr};
  m.grains.push_back({80, 60, 30});
  m.grains.push_back({120, 60, 30});
  return m;
}
inline constexpr double kVPocketAmplitude = 4;

}  // namespace softdrop::test
