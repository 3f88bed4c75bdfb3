// Charts: axes with round ticks, series as lines, markers and error bars, a legend.
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "picture_file.hpp"
#include "softdrop/render.hpp"
#include "svg_text.hpp"

namespace softdrop {
using detail::set;
using detail::show_text;
using detail::write_picture;
namespace {

// Tick positions 1, 2 or 5 x 10^k covering [lo, hi] with about `count` ticks.
std::vector<double> nice_ticks(double lo, double hi, int count) {
  const double span = hi - lo;
  const double raw = span / count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 5.0, 10.0})
    if (f * mag >= 0.75 * raw) {  // at least about `count` ticks, rather than at most
      step = f * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span; t += step)
    ticks.push_back(std::abs(t) < 1e-12 * span ? 0.0 : t);
  return ticks;
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

void render_chart(const Chart& chart, const RenderStyle& style, const std::string& path) {
  std::string why;
  if (!style.IsValid(&why)) throw std::invalid_argument(why);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Series& s : chart.series) {
    if (s.x.size() != s.y.size() || (!s.err.empty() && s.err.size() != s.y.size()))
      throw std::invalid_argument("chart: series '" + s.label + "' has mismatched lengths");
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const double e = s.err.empty() ? 0.0 : s.err[i];
      x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i] - e), y1 = std::max(y1, s.y[i] + e);
    }
  }
  for (double m : chart.markers) x0 = std::min(x0, m), x1 = std::max(x1, m);
  for (double h : chart.hlines) y0 = std::min(y0, h), y1 = std::max(y1, h);
  if (!std::isfinite(x0) || !std::isfinite(y0)) throw std::invalid_argument("chart: no data");
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 <= y0) y1 = y0 + std::max(1e-3, 0.05 * std::abs(y0));
  const double xpad = 0.015 * (x1 - x0);  // keeps markers and end points off the frame
  x0 -= xpad;
  x1 += xpad;
  const double pad = 0.05 * (y1 - y0);
  y0 -= pad;
  y1 += pad;
  const int w = style.width, h = static_cast<int>(std::lround(0.62 * style.width));
  write_picture(path, w, h, style.dpi, [&](cairo_t* cr) {
    set(cr, style.background);
    cairo_paint(cr);
    const double font = std::max(10.0, 0.022 * w);
    const double left = style.margin + 4.5 * font, right = w - style.margin - font;
    const double top = style.margin + (chart.title.empty() ? font : 2.2 * font), bottom = h - style.margin - 3 * font;
    auto px = [&](double x) { return left + (right - left) * (x - x0) / (x1 - x0); };
    auto py = [&](double y) { return bottom - (bottom - top) * (y - y0) / (y1 - y0); };
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, font);
    cairo_set_line_width(cr, 1);
    cairo_text_extents_t ext;
    const Rgba grid{0.9, 0.9, 0.9, 1};
    for (double t : nice_ticks(x0, x1, 6)) {  // x ticks and grid
      set(cr, grid);
      cairo_move_to(cr, px(t), top);
      cairo_line_to(cr, px(t), bottom);
      cairo_stroke(cr);
      set(cr, style.text);
      const std::string label = tick_label(t);
      cairo_text_extents(cr, label.c_str(), &ext);
      cairo_move_to(cr, px(t) - ext.width / 2, bottom + 1.3 * font);
      show_text(cr, label);
    }
    for (double t : nice_ticks(y0, y1, 5)) {  // y ticks and grid
      set(cr, grid);
      cairo_move_to(cr, left, py(t));
      cairo_line_to(cr, right, py(t));
      cairo_stroke(cr);
      set(cr, style.text);
      const std::string label = tick_label(t);
      cairo_text_extents(cr, label.c_str(), &ext);
      cairo_move_to(cr, left - ext.width - 0.4 * font, py(t) + 0.35 * font);
      show_text(cr, label);
    }
    set(cr, style.text);
    cairo_rectangle(cr, left, top, right - left, bottom - top);
    cairo_stroke(cr);
    cairo_text_extents(cr, chart.x_label.c_str(), &ext);
    cairo_move_to(cr, (left + right) / 2 - ext.width / 2, h - style.margin - 0.3 * font);
    show_text(cr, chart.x_label);
    cairo_save(cr);
    cairo_text_extents(cr, chart.y_label.c_str(), &ext);
    cairo_move_to(cr, style.margin + font, (top + bottom) / 2 + ext.width / 2);
    cairo_rotate(cr, -M_PI / 2);
    show_text(cr, chart.y_label);
    cairo_restore(cr);
    if (!chart.title.empty()) {
      cairo_text_extents(cr, chart.title.c_str(), &ext);
      cairo_move_to(cr, (left + right) / 2 - ext.width / 2, style.margin + font);
      show_text(cr, chart.title);
    }
    cairo_save(cr);
    cairo_rectangle(cr, left, top, right - left, bottom - top);
    cairo_clip(cr);
    const double dash[] = {5, 4}, dots[] = {1.5, 3};
    set(cr, Rgba{0.35, 0.35, 0.35, 1});
    cairo_set_dash(cr, dots, 2, 0);
    for (double y : chart.hlines) {
      cairo_move_to(cr, left, py(y));
      cairo_line_to(cr, right, py(y));
      cairo_stroke(cr);
    }
    cairo_set_dash(cr, dash, 2, 0);
    for (std::size_t i = 0; i < chart.markers.size(); ++i) {
      cairo_move_to(cr, px(chart.markers[i]), top);
      cairo_line_to(cr, px(chart.markers[i]), bottom);
      cairo_stroke(cr);
      if (i < chart.marker_labels.size()) {  // near the bottom, on the inner side of the line
        const std::string& label = chart.marker_labels[i];
        cairo_text_extents(cr, label.c_str(), &ext);
        const double x = px(chart.markers[i]);
        cairo_move_to(cr, x > (left + right) / 2 ? x - ext.x_advance - 0.3 * font : x + 0.3 * font,
                      bottom - 0.5 * font);
        show_text(cr, label);
      }
    }
    cairo_set_dash(cr, nullptr, 0, 0);
    for (const Series& s : chart.series) {  // the data
      if (s.x.empty()) continue;
      set(cr, s.colour);
      cairo_set_line_width(cr, s.style == Series::Style::points ? 1.2 : s.width);
      if (!s.err.empty())
        for (std::size_t i = 0; i < s.x.size(); ++i) {  // the bar and its caps
          const double x = px(s.x[i]), lo = py(s.y[i] - s.err[i]), hi = py(s.y[i] + s.err[i]), cap = 0.3 * font;
          cairo_move_to(cr, x, lo);
          cairo_line_to(cr, x, hi);
          cairo_move_to(cr, x - cap, lo);
          cairo_line_to(cr, x + cap, lo);
          cairo_move_to(cr, x - cap, hi);
          cairo_line_to(cr, x + cap, hi);
          cairo_stroke(cr);
        }
      if (s.style == Series::Style::points) {
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          cairo_new_sub_path(cr);
          cairo_arc(cr, px(s.x[i]), py(s.y[i]), s.width, 0, 2 * M_PI);
        }
        cairo_fill(cr);
        continue;
      }
      cairo_move_to(cr, px(s.x[0]), py(s.y[0]));
      for (std::size_t i = 1; i < s.x.size(); ++i) {
        if (s.style == Series::Style::steps) cairo_line_to(cr, px(s.x[i]), py(s.y[i - 1]));
        cairo_line_to(cr, px(s.x[i]), py(s.y[i]));
      }
      cairo_stroke(cr);
    }
    cairo_restore(cr);
    // Legend: its font shrinks until the longest entry fits inside the plot; it goes to the corner
    // that covers the fewest data (points, and lines sampled every few pixels), top right on a tie.
    double widest = 0;
    int entries = 0;
    for (const Series& s : chart.series)
      if (!s.label.empty()) {
        cairo_text_extents(cr, s.label.c_str(), &ext);
        widest = std::max(widest, ext.x_advance);
        ++entries;
      }
    const double lf = widest + 3.4 * font > right - left ? font * (right - left) / (widest + 3.4 * font) : font;
    cairo_set_font_size(cr, lf);
    const double box_w = widest + 3.4 * lf, box_h = 1.4 * lf * entries + 0.5 * lf;
    const std::array<std::array<double, 2>, 4> corners{{{right - box_w, top},  // x, y of the box's top left
                                                        {left, top},
                                                        {right - box_w, bottom - box_h},
                                                        {left, bottom - box_h}}};
    std::array<long, 4> covered{};
    auto cover = [&](double x, double y) {
      for (std::size_t c = 0; c < corners.size(); ++c)
        covered[c] +=
            x >= corners[c][0] && x <= corners[c][0] + box_w && y >= corners[c][1] && y <= corners[c][1] + box_h;
    };
    for (const Series& s : chart.series)
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        const double xa = px(s.x[i]), ya = py(s.y[i]);
        cover(xa, ya);
        if (s.style == Series::Style::points || i + 1 == s.x.size()) continue;
        const double xb = px(s.x[i + 1]), yb = py(s.y[i + 1]);
        const int n = static_cast<int>(std::min(1000.0, std::hypot(xb - xa, yb - ya) / 3));
        for (int k = 1; k < n; ++k) cover(xa + (xb - xa) * k / n, ya + (yb - ya) * k / n);
      }
    const std::size_t best =
        static_cast<std::size_t>(std::min_element(covered.begin(), covered.end()) - covered.begin());
    double ly = corners[best][1] + 1.4 * lf;
    for (const Series& s : chart.series) {
      if (s.label.empty()) continue;
      cairo_text_extents(cr, s.label.c_str(), &ext);
      const double lx = corners[best][0] + box_w - ext.x_advance - 3.2 * lf;
      set(cr, s.colour);
      if (s.style == Series::Style::points) {
        cairo_arc(cr, lx + 1.2 * lf, ly - 0.35 * lf, std::max(2.5, s.width), 0, 2 * M_PI);
        cairo_fill(cr);
      } else {
        cairo_set_line_width(cr, s.width);
        cairo_move_to(cr, lx, ly - 0.35 * lf);
        cairo_line_to(cr, lx + 2.4 * lf, ly - 0.35 * lf);
        cairo_stroke(cr);
      }
      set(cr, style.text);
      cairo_move_to(cr, lx + 2.8 * lf, ly);
      show_text(cr, s.label);
      ly += 1.4 * lf;
    }
  });
}

}  // namespace softdrop
