// Making a candidate arrangement from its parent: grain jumps checked against the spacing rule.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "media/spacing.hpp"
#include "softdrop/search.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {

// A uniform point in the disc of radius `radius`, by rejection from the square (portable: it uses
// only Rng::uniform, and the acceptance rate is pi/4).
void random_jump(Rng& rng, double radius, double* dx, double* dy) {
  for (;;) {
    const double u = rng.uniform(-1.0, 1.0), v = rng.uniform(-1.0, 1.0);
    if (u * u + v * v <= 1.0) {
      *dx = u * radius;
      *dy = v * radius;
      return;
    }
  }
}

// Brings x back into [0, width) after a jump shorter than the width.
double wrap(double x, double width) {
  if (x < 0) return x + width;
  if (x >= width) return x - width;
  return x;
}

// A grain the droplet did not touch, uniformly (any grain if it touched them all).
int untouched_grain(const std::vector<std::int32_t>& touched, int n, Rng& rng) {
  const auto free = static_cast<std::uint64_t>(n) - touched.size();
  if (free == 0) return static_cast<int>(rng.below(static_cast<std::uint64_t>(n)));
  auto k = rng.below(free);  // the k-th grain not in the (ascending) touched list
  int i = 0;
  for (std::size_t t = 0;; ++i) {
    while (t < touched.size() && touched[t] < i) ++t;
    if (t < touched.size() && touched[t] == i) continue;
    if (k-- == 0) return i;
  }
}

// Puts grain i next to a random point of the path inside the medium: its centre uniformly in the
// disc of radius (droplet radius + r) about the point. Redrawn (point and place) while the spacing
// rule refuses it; returns 1 if it moved.
int try_relocate(int i, const Evaluation& parent, double droplet_radius, const Medium& m, Rng& rng, int max_redraws,
                 SpacingIndex& index_of) {
  std::vector<std::size_t> inside;
  for (std::size_t p = 0; p < parent.path_y.size(); ++p)
    if (parent.path_y[p] > 0 && parent.path_y[p] < m.height) inside.push_back(p);
  if (inside.empty()) return 0;
  const Grain old = index_of.grain(i);
  for (int attempt = 0; attempt <= max_redraws; ++attempt) {
    const std::size_t p = inside[rng.below(inside.size())];
    double dx = 0, dy = 0;
    random_jump(rng, droplet_radius + old.r, &dx, &dy);
    double x = parent.path_x[p] + dx;
    if (m.periodic) x -= m.width * std::floor(x / m.width);
    const Grain g{x, parent.path_y[p] + dy, old.r};
    if (m.periodic && !(g.x >= 0 && g.x < m.width)) continue;
    if (index_of.can_move(i, g)) {
      index_of.move(i, g);
      return 1;
    }
  }
  return 0;
}

}  // namespace

MoveKind move_kind(std::int64_t generation, const SearchOptions& options) {
  if (generation <= 0) return MoveKind::initial;
  if (options.strategy.kind == StrategyKind::cmaes) return MoveKind::all;  // every grain, every generation
  if (options.single_every > 0 && generation % options.single_every == 0) return MoveKind::single;
  if (options.relocate_every > 0 && generation % options.relocate_every == 0) return MoveKind::relocate;
  return MoveKind::all;
}

Candidate make_candidate(const Configuration& parent, std::int64_t generation, int index,
                         const SearchOptions& options) {
  const MoveKind kind = move_kind(generation, options);
  return make_move(
      parent, kind, kind == MoveKind::single ? options.single_step : options.step,
      derive_seed(derive_seed(options.seed, static_cast<std::uint64_t>(generation)), static_cast<std::uint64_t>(index)),
      index, options);
}

Candidate make_move(const Configuration& parent, MoveKind kind, double radius, std::uint64_t stream, int index,
                    const SearchOptions& options) {
  const Medium& m = parent.medium;
  Candidate c;
  c.index = index;
  c.kind = kind;
  c.medium = m;
  Rng rng(stream);
  if (m.grains.empty()) return c;

  double r_max = 0;
  for (const Grain& g : m.grains) r_max = std::max(r_max, g.r);
  SpacingIndex index_of(m.width, m.height, m.periodic, options.gap, r_max);
  for (const Grain& g : m.grains) index_of.insert(g);

  // Grains move one after another, each checked against the others' current places, so the
  // arrangement satisfies the rule after every single jump (and a refused grain keeps its place).
  auto try_jump = [&](int i) {
    const Grain old = index_of.grain(i);
    for (int attempt = 0; attempt <= options.max_redraws; ++attempt) {
      double dx = 0, dy = 0;
      random_jump(rng, radius, &dx, &dy);
      const Grain g{m.periodic ? wrap(old.x + dx, m.width) : old.x + dx, old.y + dy, old.r};
      if (index_of.can_move(i, g)) {
        index_of.move(i, g);
        c.medium.grains[static_cast<std::size_t>(i)] = g;
        return 1;
      }
    }
    return 0;
  };

  const int n = static_cast<int>(m.grains.size());
  if (c.kind == MoveKind::relocate) {
    c.moved_grain = untouched_grain(parent.eval.touched, n, rng);
    c.moved = try_relocate(c.moved_grain, parent.eval, options.droplet.radius, m, rng, options.max_redraws, index_of);
    if (c.moved) c.medium.grains[static_cast<std::size_t>(c.moved_grain)] = index_of.grain(c.moved_grain);
  } else if (c.kind == MoveKind::single) {
    const auto& touched = parent.eval.touched;
    c.moved_grain = touched.empty() ? static_cast<int>(rng.below(static_cast<std::uint64_t>(n)))
                                    : touched[rng.below(touched.size())];
    c.moved = try_jump(c.moved_grain);
  } else {
    for (int i = 0; i < n; ++i) c.moved += try_jump(i);
  }

  if (auto bad = find_spacing_violation(c.medium, options.gap))
    throw std::logic_error("make_candidate: grains " + std::to_string(bad->first) + " and " +
                           std::to_string(bad->second) + " break the spacing rule after a move");
  return c;
}

}  // namespace softdrop
