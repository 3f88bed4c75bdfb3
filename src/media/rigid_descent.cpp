#include "rigid_descent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "util/validation.hpp"

namespace softdrop {
namespace {

constexpr double kPi = std::numbers::pi;
// Positions are exact to about 1e-12 of the box; a contact closer than this is the one just left.
constexpr double kTolerance = 1e-7;
// A descent is a strictly falling sequence of contacts; more than this many means a numerical
// cycle.
constexpr int kMaxEvents = 100000;
// A recorded path samples arcs at least this often (radians): chords 2e-5 shorter than the arcs.
constexpr double kPathStep = 0.02;

struct Disc {
  double x, y, r;  // a grain dilated by the body's radius; periodic media hold three images
};

struct Vec {
  double x, y;
};
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y; }

// The centre's walk: a state machine of falls and slides on the dilated grains.
class Walk {
 public:
  Walk(const Medium& m, double radius) : width_(m.width), height_(m.height), periodic_(m.periodic) {
    const int images = m.periodic ? 1 : 0;
    for (int image = -images; image <= images; ++image)
      for (const Grain& g : m.grains) discs_.push_back({g.x + image * m.width, g.y, g.r + radius});
    per_image_ = static_cast<int>(m.grains.size());
    lo_ = m.periodic ? -std::numeric_limits<double>::infinity() : radius;
    hi_ = m.periodic ? std::numeric_limits<double>::infinity() : m.width - radius;
    double top = m.height;
    for (const Disc& d : discs_) top = std::max(top, d.y + d.r);
    start_y_ = top + 1;
  }

  RigidDescent run(double x0, bool record_path) {
    x_ = std::clamp(x0, lo_, hi_), y_ = start_y_, length_ = 0, shift_ = 0;
    RigidDescent out;
    path_ = record_path ? &out : nullptr;
    record();
    int next = kFall;
    for (int events = 0; events < kMaxEvents && next != kStuck && next != kPassed; ++events) {
      next = next == kFall ? fall() : slide(next);
      if (next >= 0) ++out.slides;
    }
    out.passed = next == kPassed;
    out.tortuosity = out.passed ? length_ / height_ : std::numeric_limits<double>::quiet_NaN();
    out.x = periodic_ ? x_ - width_ * std::floor(x_ / width_) : x_, out.y = y_;
    return out;
  }

 private:
  // What comes next, besides sliding along a disc (its index, >= 0).
  static constexpr int kFall = -1, kStuck = -2, kPassed = -3;

  // Falls from (x_, y_) onto the highest disc top below and returns it, or kPassed.
  int fall() {
    if (periodic_) shift(-width_ * std::floor(x_ / width_));
    int best = -1;
    double best_y = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(discs_.size()); ++i) {
      const Disc& d = discs_[i];
      const double dx = x_ - d.x;
      if (std::abs(dx) >= d.r) continue;
      const double top = d.y + std::sqrt(d.r * d.r - dx * dx);
      if (top < y_ - kTolerance && top > best_y) best = i, best_y = top;
    }
    if (best < 0 || best_y < 0) best_y = 0, best = kPassed;
    length_ += band(y_, best_y);
    y_ = best_y;
    record();
    return best;
  }

  // Slides along the upper half of disc k towards its widest point on the side it is on. Returns
  // the next disc to slide along, kFall, kPassed (it crossed y = 0 on the way) or kStuck.
  int slide(int k) {
    const Disc& d = discs_[k];
    const double from = std::atan2(y_ - d.y, x_ - d.x);
    const double dir = x_ >= d.x ? -1.0 : 1.0;  // right half towards 0, left half towards pi
    const double end = dir < 0 ? 0.0 : kPi;
    double stop = end;
    int next = kFall;
    bool wall = false;
    for (int h = 0; h < static_cast<int>(discs_.size()); ++h) {
      if (h == k) continue;
      const Disc& e = discs_[h];
      const double dist = std::hypot(e.x - d.x, e.y - d.y);
      if (dist >= d.r + e.r || dist <= std::abs(d.r - e.r)) continue;
      const double base = std::atan2(e.y - d.y, e.x - d.x);
      const double half = std::acos(std::clamp((d.r * d.r + dist * dist - e.r * e.r) / (2 * d.r * dist), -1.0, 1.0));
      for (double a : {base + half, base - half}) {
        a = std::remainder(a, 2 * kPi);
        const double travel = (a - from) * dir;
        // A meeting point where it stands counts (it may have landed in a notch) unless it is
        // leaving that disc there, as it does from the corner it just turned.
        if (travel < -kTolerance / d.r || travel >= (stop - from) * dir) continue;
        const Vec p{d.x + d.r * std::cos(a), d.y + d.r * std::sin(a)};
        const Vec along{-std::sin(a) * dir, std::cos(a) * dir};
        if (dot(along, {(p.x - e.x) / e.r, (p.y - e.y) / e.r}) >= -1e-9) continue;
        stop = a, next = h;
      }
    }
    // A side wall met on the way: the wedge between it and a grain's upper half is a dead end.
    const double wall_x = dir < 0 ? hi_ : lo_;
    if (std::abs(wall_x - d.x) < d.r) {
      const double a = std::acos((wall_x - d.x) / d.r);
      if ((a - from) * dir > 0 && (a - from) * dir < (stop - from) * dir) stop = a, next = kFall, wall = true;
    }
    if (move_along(d, from, stop)) return kPassed;
    if (wall) return kStuck;
    return next == kFall ? kFall : corner(k, next);
  }

  // At the meeting point of discs k and h: the steepest descending direction open to the body
  // (gravity projected on the cone outside both). Returns kFall, h (slide along it) or kStuck.
  int corner(int k, int h) {
    const Disc& d = discs_[k];
    const Disc& e = discs_[h];
    const Vec nk{(x_ - d.x) / d.r, (y_ - d.y) / d.r};
    const Vec nh{(x_ - e.x) / e.r, (y_ - e.y) / e.r};
    const Vec options[] = {{0, -1}, {-nk.y, nk.x}, {nk.y, -nk.x}, {-nh.y, nh.x}, {nh.y, -nh.x}};
    int best = -1;
    double best_y = -kTolerance;
    for (int i = 0; i < 5; ++i)
      if (dot(options[i], nk) >= -1e-12 && dot(options[i], nh) >= -1e-12 && options[i].y < best_y)
        best = i, best_y = options[i].y;
    if (best == 0) return kFall;
    if (best >= 3 && nh.y > 0) return rebase(h);  // down e's upper half
    // No descending direction, or one only along a lower half (the far side of the lens of two
    // grains, which the body cannot reach from where it came): a dead end.
    return kStuck;
  }

  // Keeps the centre within the periodic box's first image while it slides from disc to disc.
  int rebase(int h) {
    if (!periodic_) return h;
    const int image = h / per_image_;  // 0, 1, 2: left, middle, right copies
    if (x_ >= width_ && image > 0) shift(-width_), h -= per_image_;
    if (x_ < 0 && image < 2) shift(width_), h += per_image_;
    return h;
  }

  // Moves the centre to another image of itself; the recorded path stays continuous.
  void shift(double dx) { x_ += dx, shift_ -= dx; }

  void record() {
    if (!path_) return;
    path_->path_x.push_back(x_ + shift_);
    path_->path_y.push_back(y_);
  }

  // Moves the centre along the upper half of d from angle `from` to `to` (the same side); true if
  // it crossed y = 0 on the way (it stops there).
  bool move_along(const Disc& d, double from, double to) {
    const double y_from = d.y + d.r * std::sin(from), y_to = d.y + d.r * std::sin(to);
    // The angle at height y on this side of the disc.
    const auto angle = [&](double y) {
      const double a = std::asin(std::clamp((y - d.y) / d.r, -1.0, 1.0));
      return to < kPi / 2 ? a : kPi - a;
    };
    const double upper = std::min(y_from, height_), lower = std::max(y_to, 0.0);
    if (upper > lower) length_ += d.r * std::abs(angle(upper) - angle(lower));
    const bool crossed = y_to < 0;
    const double at = crossed ? angle(0.0) : to;
    const int pieces = path_ ? static_cast<int>(std::ceil(std::abs(at - from) / kPathStep)) : 1;
    for (int i = 1; i <= pieces; ++i) {
      const double a = i == pieces ? at : from + (at - from) * i / pieces;
      x_ = d.x + d.r * std::cos(a), y_ = d.y + d.r * std::sin(a);
      if (i < pieces) record();
    }
    if (crossed) y_ = 0.0;
    record();
    return crossed;
  }

  // Length of a vertical drop from y0 to y1 that lies between y = 0 and y = H.
  double band(double y0, double y1) const { return std::max(0.0, std::min(y0, height_) - std::max(y1, 0.0)); }

  std::vector<Disc> discs_;
  int per_image_ = 0;
  double width_, height_;
  bool periodic_;
  double lo_, hi_, start_y_;
  double x_ = 0, y_ = 0, length_ = 0;
  double shift_ = 0;              // the recorded path's x is x_ + shift_ (no periodic jumps)
  RigidDescent* path_ = nullptr;  // where to record the path, if asked
};

}  // namespace

namespace {

void check(const Medium& medium, double radius) {
  std::string why;
  if (!medium.IsValid(&why)) throw std::invalid_argument(why);
  if (!(std::isfinite(radius) && radius >= 0))
    throw std::invalid_argument("radius = " + detail::num(radius) + ": must be finite and >= 0");
  // Between walls the disc must fit; in a periodic box it would overlap its own image, as a grain
  // may not (Medium::IsValid), and past that its dilated grains lose every digit of the medium.
  if (medium.periodic ? 2 * radius >= medium.width : 2 * radius > medium.width)
    throw std::invalid_argument("radius = " + detail::num(radius) + ": the disc is wider than the box" +
                                (medium.periodic ? " (its diameter must be < width)" : ""));
}

void check_start(const Medium& medium, double x0) {
  if (!(x0 >= 0 && x0 <= medium.width))
    throw std::invalid_argument("x0 = " + detail::num(x0) + ": must be in [0, width]");
}

}  // namespace

RigidDescent rigid_descent(const Medium& medium, double radius, double x0, bool record_path) {
  return rigid_descents(medium, radius, {x0}, record_path).front();
}

std::vector<RigidDescent> rigid_descents(const Medium& medium, double radius, const std::vector<double>& x0s,
                                         bool record_paths) {
  check(medium, radius);
  for (double x0 : x0s) check_start(medium, x0);
  Walk walk(medium, radius);
  std::vector<RigidDescent> out;
  out.reserve(x0s.size());
  for (double x0 : x0s) out.push_back(walk.run(x0, record_paths));
  return out;
}

}  // namespace softdrop
