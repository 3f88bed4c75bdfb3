// Drawing with Cairo: scenes (medium, filled grains, polylines, caption), charts and GIF frames.
#include "softdrop/render.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "animation_sinks.hpp"
#include "temp_files.hpp"
#include "svg_text.hpp"
#include "validation.hpp"

namespace softdrop {
using detail::fail;
using detail::num;
using detail::show_text;

ImageFormat image_format_for(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".svg") return ImageFormat::svg;
  if (ext == ".pdf") return ImageFormat::pdf;
  if (ext == ".gif") return ImageFormat::gif;
  if (ext == ".mp4") return ImageFormat::mp4;
  throw std::invalid_argument("output '" + path + "': unknown picture format (use .png, .svg, .pdf, or .gif / .mp4 for animations)");
}

Rgba parse_colour(const std::string& text) {
  // The '#' is optional: config files (CLI11's TOML reader) take '#' for a comment even in quotes.
  const std::size_t o = !text.empty() && text[0] == '#' ? 1 : 0;
  const auto bad = [&] { return std::invalid_argument("colour '" + text + "': expected #rrggbb or #rrggbbaa"); };
  if (text.size() - o != 6 && text.size() - o != 8) throw bad();
  auto hex = [&](std::size_t i) -> double {
    const std::string two = text.substr(o + i, 2);
    if (!std::isxdigit(static_cast<unsigned char>(two[0])) || !std::isxdigit(static_cast<unsigned char>(two[1]))) throw bad();
    return std::stoi(two, nullptr, 16) / 255.0;
  };
  return {hex(0), hex(2), hex(4), text.size() - o == 8 ? hex(6) : 1.0};
}

bool RenderStyle::IsValid(std::string* why) const {
  if (width < 16 || width > 10000) return fail(why, "size = " + std::to_string(width) + ": must be in [16, 10000] points");
  if (!(dpi >= 36 && dpi <= 1200)) return fail(why, "dpi = " + num(dpi) + ": must be in [36, 1200]");
  if (width * dpi / 72 > 20000) return fail(why, "size = " + std::to_string(width) + " at dpi = " + num(dpi) + ": more than 20000 pixels wide");
  if (!std::isfinite(grain_line) || grain_line <= 0) return fail(why, "grain-line = " + num(grain_line) + ": must be > 0");
  if (!std::isfinite(margin) || margin < 0) return fail(why, "margin = " + num(margin) + ": must be >= 0");
  return true;
}

namespace {

using CairoPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;
using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

void set(cairo_t* cr, const Rgba& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

// Where the medium lands on the picture: picture = (margin + s (x - x0), margin + s (y1 - y)).
struct Geometry {
  double y0 = 0, y1 = 0;  // medium-y range shown
  double scale = 1;
  int width = 0, height = 0;
  double caption_height = 0;
};

Geometry geometry_of(const Scene& scene, const RenderStyle& style) {
  const Medium& m = scene.medium;
  Geometry g;
  g.y0 = 0;
  g.y1 = m.height;
  if (scene.top_room >= 0) {
    g.y1 = m.height + scene.top_room;
  } else {
    for (const Polyline& p : scene.lines)
      for (double y : p.y) g.y1 = std::max(g.y1, y), g.y0 = std::min(g.y0, y);
  }
  g.y0 = std::max(g.y0, -0.1 * m.height);  // a path leaves through the bottom; show only its start
  g.width = style.width;
  g.scale = (style.width - 2 * style.margin) / m.width;
  g.caption_height = style.caption && !scene.caption.empty() ? std::max(11.0, 0.02 * style.width) * 1.6 : 0;
  g.height = static_cast<int>(std::ceil(2 * style.margin + g.scale * (g.y1 - g.y0) + g.caption_height));
  return g;
}

// Wraps an unwrapped periodic polyline into [0, W): a new piece starts where it crosses an edge.
std::vector<std::vector<std::pair<double, double>>> pieces_of(const Polyline& p, const Medium& m) {
  std::vector<std::vector<std::pair<double, double>>> out(1);
  long previous_cell = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    double x = p.x[i];
    long cell = 0;
    if (m.periodic && !p.closed) {
      cell = static_cast<long>(std::floor(x / m.width));
      x -= static_cast<double>(cell) * m.width;
      if (i > 0 && cell != previous_cell) {
        // Finish this piece just across the edge, start the next one from just across the other.
        const double shift = static_cast<double>(cell - previous_cell) * m.width;
        out.back().emplace_back(x + shift, p.y[i]);
        out.emplace_back();
        out.back().emplace_back(p.x[i - 1] - static_cast<double>(cell) * m.width, p.y[i - 1]);
      }
    } else if (m.periodic && p.closed) {
      // A ring is drawn whole, shifted so that its first point lies inside the box.
      cell = static_cast<long>(std::floor(p.x[0] / m.width));
      x -= static_cast<double>(cell) * m.width;
    }
    previous_cell = cell;
    out.back().emplace_back(x, p.y[i]);
  }
  return out;
}

void draw_scene(cairo_t* cr, const Scene& scene, const RenderStyle& style, const Geometry& g) {
  const Medium& m = scene.medium;
  auto px = [&](double x) { return style.margin + g.scale * x; };
  auto py = [&](double y) { return style.margin + g.scale * (g.y1 - y); };
  set(cr, style.background);
  cairo_paint(cr);

  cairo_save(cr);
  cairo_rectangle(cr, px(0), py(g.y1), g.scale * m.width, g.scale * (g.y1 - g.y0));
  cairo_clip(cr);
  // Grains, with their periodic images at the edges; each grain is one path (or, solid, all of
  // them one path, filled with the nonzero rule: their union).
  auto images = [&](const Grain& gr) {
    std::vector<double> xs{gr.x};
    if (m.periodic) {
      if (gr.x - gr.r < 0) xs.push_back(gr.x + m.width);
      if (gr.x + gr.r > m.width) xs.push_back(gr.x - m.width);
    }
    return xs;
  };
  if (style.solid_grains) {
    cairo_new_path(cr);
    for (const Grain& gr : m.grains)
      for (double x : images(gr)) {
        cairo_new_sub_path(cr);
        cairo_arc(cr, px(x), py(gr.y), g.scale * gr.r, 0, 2 * M_PI);
      }
    set(cr, style.solid);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
    cairo_fill(cr);
  }
  for (std::size_t i = 0; i < m.grains.size(); ++i) {
    const Grain& gr = m.grains[i];
    const bool fill = i < scene.filled.size() && scene.filled[i];
    if (style.solid_grains && !fill) continue;
    for (double x : images(gr)) {
      cairo_new_path(cr);
      cairo_arc(cr, px(x), py(gr.y), g.scale * gr.r, 0, 2 * M_PI);
      if (fill) {
        set(cr, style.touched);
        if (style.solid_grains) {
          cairo_fill(cr);
          continue;
        }
        cairo_fill_preserve(cr);
      }
      set(cr, style.grain);
      cairo_set_line_width(cr, style.grain_line);
      cairo_stroke(cr);
    }
  }
  // Polylines on top.
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const Polyline& p : scene.lines) {
    if (p.x.size() < 2) continue;
    for (const auto& piece : pieces_of(p, m)) {
      if (piece.size() < 2) continue;
      cairo_new_path(cr);
      cairo_move_to(cr, px(piece[0].first), py(piece[0].second));
      for (std::size_t i = 1; i < piece.size(); ++i) cairo_line_to(cr, px(piece[i].first), py(piece[i].second));
      if (p.closed) {
        cairo_close_path(cr);
        if (p.fill.a > 0) {
          set(cr, p.fill);
          cairo_fill_preserve(cr);
        }
      }
      set(cr, p.colour);
      cairo_set_line_width(cr, p.width);
      cairo_stroke(cr);
    }
  }
  if (!scene.labels.empty()) {
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, std::max(9.0, 0.016 * g.width));
    for (const Label& l : scene.labels) {
      set(cr, l.colour);
      cairo_move_to(cr, px(l.x), py(l.y));
      show_text(cr, l.text);
    }
  }
  cairo_restore(cr);

  // The medium's box (dashed above the top, where the droplet starts).
  set(cr, style.box);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, px(0), py(m.height), g.scale * m.width, g.scale * m.height);
  cairo_stroke(cr);

  if (style.scale_bar) {  // 1, 2 or 5 times a power of ten, about a fifth of the width
    const double target = 0.2 * m.width, power = std::pow(10.0, std::floor(std::log10(target)));
    const double length = target >= 5 * power ? 5 * power : target >= 2 * power ? 2 * power : power;
    const double font = std::max(9.0, 0.018 * g.width), x0 = px(0) + font, y0 = py(0) - font;
    const std::string label = detail::num(length) + " length units";
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, font);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, label.c_str(), &ext);
    set(cr, Rgba{style.background.r, style.background.g, style.background.b, 0.8});  // legible over grains
    cairo_rectangle(cr, x0 - 0.3 * font, y0 - 1.9 * font, std::max(g.scale * length, ext.x_advance) + 0.6 * font,
                    2.4 * font);
    cairo_fill(cr);
    set(cr, style.text);
    cairo_set_line_width(cr, std::max(2.0, 0.25 * font));
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x0 + g.scale * length, y0);
    cairo_stroke(cr);
    cairo_move_to(cr, x0, y0 - 0.6 * font);
    show_text(cr, label);
  }

  if (g.caption_height > 0) {
    set(cr, style.text);
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    // Shrink the font until the caption fits the width.
    double font = g.caption_height / 1.6;
    cairo_set_font_size(cr, font);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, scene.caption.c_str(), &ext);
    const double room = g.width - 2 * style.margin;
    if (ext.x_advance > room) cairo_set_font_size(cr, font * room / ext.x_advance);
    cairo_move_to(cr, style.margin, g.height - style.margin - 0.3 * g.caption_height);
    show_text(cr, scene.caption);
  }
}

// Draws with `paint(cr)` on a surface of the format of `path`, into a temporary file renamed over
// `path` on success.
void write_picture(const std::string& path, int width, int height, double dpi,
                   const std::function<void(cairo_t*)>& paint) {
  const ImageFormat format = image_format_for(path);
  const double scale = format == ImageFormat::png ? dpi / 72 : 1.0;  // pixels a point
  const detail::TempName tmp_name(path);
  const std::string& tmp = tmp_name.str();
  cairo_surface_t* raw = nullptr;
  switch (format) {
    case ImageFormat::png:
      raw = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(std::ceil(width * scale)),
                                       static_cast<int>(std::ceil(height * scale)));
      break;
    case ImageFormat::svg: raw = cairo_svg_surface_create(tmp.c_str(), width, height); break;
    case ImageFormat::pdf: raw = cairo_pdf_surface_create(tmp.c_str(), width, height); break;
    case ImageFormat::gif:
    case ImageFormat::mp4:
      throw std::invalid_argument("output '" + path + "': a still picture is written as .png, .svg or .pdf");
  }
  SurfacePtr surface(raw, cairo_surface_destroy);
  auto failed = [&](const std::string& what) {
    std::filesystem::remove(tmp);
    return std::runtime_error("output '" + path + "': " + what);
  };
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw failed(cairo_status_to_string(cairo_surface_status(surface.get())));
  std::vector<detail::SvgText> texts;  // SVG: the words, written as <text> after the drawing
  {
    CairoPtr cr(cairo_create(surface.get()), cairo_destroy);
    if (format == ImageFormat::svg) detail::collect_svg_text(cr.get(), &texts);
    cairo_scale(cr.get(), scale, scale);
    paint(cr.get());
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS) throw failed(cairo_status_to_string(cairo_status(cr.get())));
  }
  if (format == ImageFormat::png) {
    const cairo_status_t s = cairo_surface_write_to_png(surface.get(), tmp.c_str());
    if (s != CAIRO_STATUS_SUCCESS) throw failed(cairo_status_to_string(s));
  } else {
    cairo_surface_finish(surface.get());
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
      throw failed(cairo_status_to_string(cairo_surface_status(surface.get())));
    try {
      detail::insert_svg_text(tmp, texts);
    } catch (const std::runtime_error& e) {
      throw failed(e.what());
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw failed(ec.message());
}

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
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span; t += step) ticks.push_back(std::abs(t) < 1e-12 * span ? 0.0 : t);
  return ticks;
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

void render_scene(const Scene& scene, const RenderStyle& style, const std::string& path) {
  std::string why;
  if (!style.IsValid(&why)) throw std::invalid_argument(why);
  if (!scene.medium.IsValid(&why)) throw std::invalid_argument(why);
  const Geometry g = geometry_of(scene, style);
  write_picture(path, g.width, g.height, style.dpi, [&](cairo_t* cr) { draw_scene(cr, scene, style, g); });
}

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
        cairo_move_to(cr, x > (left + right) / 2 ? x - ext.x_advance - 0.3 * font : x + 0.3 * font, bottom - 0.5 * font);
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
    // Legend, top right; its font shrinks until the longest entry fits inside the plot.
    double widest = 0;
    for (const Series& s : chart.series)
      if (!s.label.empty()) cairo_text_extents(cr, s.label.c_str(), &ext), widest = std::max(widest, ext.x_advance);
    const double lf = widest + 3.4 * font > right - left ? font * (right - left) / (widest + 3.4 * font) : font;
    cairo_set_font_size(cr, lf);
    double ly = top + 1.4 * lf;
    for (const Series& s : chart.series) {
      if (s.label.empty()) continue;
      cairo_text_extents(cr, s.label.c_str(), &ext);
      const double lx = right - ext.x_advance - 3.2 * lf;
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

void render_animation(int frames, double fps, const std::function<void(int, Scene&)>& frame,
                      const RenderStyle& style, const std::string& path) {
  std::string why;
  if (!style.IsValid(&why)) throw std::invalid_argument(why);
  const ImageFormat format = image_format_for(path);
  if (format != ImageFormat::gif && format != ImageFormat::mp4)
    throw std::invalid_argument("output '" + path + "': an animation is written as .gif or .mp4");
  if (frames < 1 || frames > 100000) throw std::invalid_argument("frames = " + std::to_string(frames) + ": must be in [1, 1e5]");
  if (!std::isfinite(fps) || fps <= 0 || fps > 100) throw std::invalid_argument("fps = " + num(fps) + ": must be in (0, 100]");

  Scene scene;
  frame(0, scene);
  if (!scene.medium.IsValid(&why)) throw std::invalid_argument(why);
  Geometry g = geometry_of(scene, style);  // fixed for all frames
  if (format == ImageFormat::mp4) {  // H.264 wants even sizes: one more row or column of background
    g.width += g.width % 2;
    g.height += g.height % 2;
  }
  std::unique_ptr<detail::FrameSink> sink = format == ImageFormat::gif
                                                ? detail::gif_sink(path, g.width, g.height, fps)
                                                : detail::video_sink(path, g.width, g.height, fps);
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, g.width, g.height), cairo_surface_destroy);
  for (int f = 0; f < frames; ++f) {
    if (f > 0) {
      scene = Scene{};
      frame(f, scene);
    }
    {
      CairoPtr cr(cairo_create(surface.get()), cairo_destroy);
      draw_scene(cr.get(), scene, style, g);
    }
    cairo_surface_flush(surface.get());
    sink->add(cairo_image_surface_get_data(surface.get()), cairo_image_surface_get_stride(surface.get()));
  }
  sink->finish();
}

}  // namespace softdrop
