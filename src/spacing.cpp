// The only translation unit that includes CGAL: keep it that way, CGAL headers are slow to compile.
#include "softdrop/spacing.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/range_search_delaunay_2.h>

#include <algorithm>
#include <cmath>
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

struct SpacingIndex::Impl {
  double width, height;
  bool periodic;
  double gap, r_max;
  std::vector<Grain> grains;  // vertex info indexes this
  Delaunay dt;
  std::vector<Delaunay::Vertex_handle> found;

  // True if some stored grain is closer than the rule allows to g placed at x offset `shift`.
  bool conflicts(const Grain& g, double shift) {
    const double reach = required_distance(g.r, r_max, gap);
    const Point centre(g.x + shift, g.y);
    found.clear();
    CGAL::range_search(dt, Circle(centre, reach * reach), std::back_inserter(found));
    for (const auto& v : found) {
      const int id = v->info().id;
      if (id < 0) continue;  // range_search's own temporary vertex
      const Grain& o = grains[static_cast<std::size_t>(id)];
      const double dx = o.x - (g.x + shift), dy = o.y - g.y;
      const double need = required_distance(g.r, o.r, gap);
      if (dx * dx + dy * dy < need * need) return true;
    }
    return false;
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

bool SpacingIndex::can_place(const Grain& g) const {
  Impl& s = *impl_;
  if (g.y - g.r < 0 || g.y + g.r > s.height) return false;
  if (!s.periodic && (g.x - g.r < 0 || g.x + g.r > s.width)) return false;
  if (s.conflicts(g, 0)) return false;
  if (s.periodic && (s.conflicts(g, -s.width) || s.conflicts(g, s.width))) return false;
  return true;
}

void SpacingIndex::insert(const Grain& g) {
  auto v = impl_->dt.insert(Point(g.x, g.y));
  v->info().id = static_cast<int>(impl_->grains.size());
  impl_->grains.push_back(g);
}

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
    points.emplace_back(Point(medium.grains[static_cast<std::size_t>(i)].x,
                              medium.grains[static_cast<std::size_t>(i)].y),
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
      CGAL::range_search(dt, Circle(Point(g.x + shift, g.y), reach * reach),
                         std::back_inserter(found));
      for (const auto& v : found) {
        const int j = v->info().id;
        if (j < 0 || j == i) continue;
        const Grain& o = medium.grains[static_cast<std::size_t>(j)];
        const double dx = o.x - (g.x + shift), dy = o.y - g.y;
        const double need = required_distance(g.r, o.r, gap);
        if (dx * dx + dy * dy < need * need) return std::pair{std::min(i, j), std::max(i, j)};
      }
    }
  }
  return std::nullopt;
}

}  // namespace softdrop
