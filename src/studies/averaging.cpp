#include "averaging.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace softdrop {

std::vector<GroupAverage> group_averages(std::vector<MediumPoint> points, AveragingType type, int group,
                                         Leftover leftover) {
  if (group < 1) throw std::invalid_argument("group = " + std::to_string(group) + ": must be >= 1");
  std::sort(points.begin(), points.end(), [type](const MediumPoint& a, const MediumPoint& b) {
    return type == AveragingType::by_t ? (a.t != b.t ? a.t < b.t : a.phi < b.phi)
                                       : (a.phi != b.phi ? a.phi < b.phi : a.t < b.t);
  });
  std::vector<GroupAverage> out;
  const std::size_t n = static_cast<std::size_t>(group);
  for (std::size_t start = 0; start < points.size(); start += n) {
    const std::size_t end = std::min(start + n, points.size());
    if (end - start < n && leftover == Leftover::drop) break;
    const int count = static_cast<int>(end - start);
    GroupAverage g;
    g.count = count;
    for (std::size_t i = start; i < end; ++i) g.phi += points[i].phi, g.t += points[i].t;
    g.phi /= count;
    g.t /= count;
    if (count > 1) {
      double sp = 0, st = 0;
      for (std::size_t i = start; i < end; ++i) {
        sp += (points[i].phi - g.phi) * (points[i].phi - g.phi);
        st += (points[i].t - g.t) * (points[i].t - g.t);
      }
      g.phi_se = std::sqrt(sp / (count - 1) / count);
      g.t_se = std::sqrt(st / (count - 1) / count);
    }
    out.push_back(g);
  }
  return out;
}

}  // namespace softdrop
