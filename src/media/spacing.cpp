// The only translation unit that includes CGAL: keep it that way, CGAL headers are slow to compile.
#include "spacing.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/range_search_delaunay_2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace softdrop {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// range_search inserts (and removes) a temporary vertex at the query centre; its info stays -1.
struct VertexInfo {
  int id = -1;
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using Point = Kernel::Point_2;
using Circle = Kernel::Circle_2;
}  // namespace

double required_distance(double a, double b, double gap) { return a + b + gap * std::max(a, b); }

namespace {
// The pair test of the rule, symmetric bit for bit in (a, b): IEEE subtraction is exactly
// antisymmetric, and the nearest periodic image is chosen from |dx| alone. Every check (placing,
// moving, verifying) goes through here, so they can never disagree at the threshold.
bool too_close(const Grain& a, const Grain& b, double width, bool periodic, double gap) {
  double dx = b.x - a.x;
  if (periodic) dx -= width * std::round(dx / width);  // nearest image; round() is odd too
  const double dy = b.y - a.y;
  const double need = required_distance(a.r, b.r, gap);
  return dx * dx + dy * dy < need * need;
}
}  // namespace

struct SpacingIndex::Impl {
  double width, height;
  bool periodic;
  double gap, r_max;
  std::vector<Grain> grains;                      // vertex info indexes this
  std::vector<Delaunay::Vertex_handle> vertices;  // grain id -> its vertex
  Delaunay dt;
  std::vector<Delaunay::Vertex_handle> found;

  // True if some stored grain other than `skip` is closer than the rule allows to g placed at x
  // offset `shift`.
  bool conflicts(const Grain& g, double shift, int skip) {
    const double reach = required_distance(g.r, r_max, gap);
    const Point centre(g.x + shift, g.y);
    found.clear();
    CGAL::range_search(dt, Circle(centre, reach * reach), std::back_inserter(found));
    for (const auto& v : found) {
      const int id = v->info().id;
      if (id < 0 || id == skip) continue;  // range_search's own temporary vertex, or the mover
      if (too_close(g, grains[static_cast<std::size_t>(id)], width, periodic, gap)) return true;
    }
    return false;
  }

  // The rule of can_place for g, ignoring grain `skip` (-1: none).
  bool fits(const Grain& g, int skip) {
    if (g.y - g.r < 0 || g.y + g.r > height) return false;
    if (!periodic && (g.x - g.r < 0 || g.x + g.r > width)) return false;
    if (conflicts(g, 0, skip)) return false;
    if (periodic && (conflicts(g, -width, skip) || conflicts(g, width, skip))) return false;
    return true;
  }
};

SpacingIndex::SpacingIndex(double width, double height, bool periodic, double gap, double r_max)
    : impl_(std::make_unique<Impl>()) {
  impl_->width = width;
  impl_->height = height;
  impl_->periodic = periodic;
  impl_->gap = gap;
  impl_->r_max = r_max;
}
SpacingIndex::~SpacingIndex() = default;
SpacingIndex::SpacingIndex(SpacingIndex&&) noexcept = default;
SpacingIndex& SpacingIndex::operator=(SpacingIndex&&) noexcept = default;

bool SpacingIndex::can_place(const Grain& g) const { return impl_->fits(g, -1); }

void SpacingIndex::insert(const Grain& g) {
  auto v = impl_->dt.insert(Point(g.x, g.y));
  v->info().id = static_cast<int>(impl_->grains.size());
  impl_->grains.push_back(g);
  impl_->vertices.push_back(v);
}

bool SpacingIndex::can_move(int i, const Grain& g) const {
  if (i < 0 || static_cast<std::size_t>(i) >= impl_->grains.size())
    throw std::out_of_range("SpacingIndex::can_move: no grain " + std::to_string(i));
  return impl_->fits(g, i);
}

void SpacingIndex::move(int i, const Grain& g) {
  Impl& s = *impl_;
  if (i < 0 || static_cast<std::size_t>(i) >= s.grains.size())
    throw std::out_of_range("SpacingIndex::move: no grain " + std::to_string(i));
  // The spacing rule keeps centres apart, so the new point never coincides with another vertex.
  auto& v = s.vertices[static_cast<std::size_t>(i)];
  v = s.dt.move(v, Point(g.x, g.y));
  v->info().id = i;
  s.grains[static_cast<std::size_t>(i)] = g;
}

const Grain& SpacingIndex::grain(int i) const { return impl_->grains.at(static_cast<std::size_t>(i)); }

std::size_t SpacingIndex::size() const { return impl_->grains.size(); }

std::optional<std::pair<int, int>> find_spacing_violation(const Medium& medium, double gap) {
  double r_max = 0;
  for (const Grain& g : medium.grains) r_max = std::max(r_max, g.r);
  const int n = static_cast<int>(medium.grains.size());
  for (int i = 0; i < n; ++i) {
    const Grain& g = medium.grains[static_cast<std::size_t>(i)];
    if (g.y - g.r < 0 || g.y + g.r > medium.height) return std::pair{i, i};
    if (!medium.periodic && (g.x - g.r < 0 || g.x + g.r > medium.width)) return std::pair{i, i};
  }
  // Build the triangulation over all grains, then ask each grain for its neighbours.
  Delaunay dt;
  std::vector<std::pair<Point, VertexInfo>> points;
  points.reserve(medium.grains.size());
  for (int i = 0; i < n; ++i)
    points.emplace_back(
        Point(medium.grains[static_cast<std::size_t>(i)].x, medium.grains[static_cast<std::size_t>(i)].y),
        VertexInfo{i});
  dt.insert(points.begin(), points.end());
  std::vector<Delaunay::Vertex_handle> found;
  for (int i = 0; i < n; ++i) {
    const Grain& g = medium.grains[static_cast<std::size_t>(i)];
    const double reach = required_distance(g.r, r_max, gap);
    const int shifts = medium.periodic ? 3 : 1;
    for (int s = 0; s < shifts; ++s) {
      const double shift = s == 0 ? 0.0 : (s == 1 ? -medium.width : medium.width);
      found.clear();
      CGAL::range_search(dt, Circle(Point(g.x + shift, g.y), reach * reach), std::back_inserter(found));
      for (const auto& v : found) {
        const int j = v->info().id;
        if (j < 0 || j == i) continue;
        if (too_close(g, medium.grains[static_cast<std::size_t>(j)], medium.width, medium.periodic, gap))
          return std::pair{std::min(i, j), std::max(i, j)};
      }
    }
  }
  return std::nullopt;
}

}  // namespace softdrop
