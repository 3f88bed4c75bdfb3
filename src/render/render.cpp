// Drawing with Cairo: scenes (medium, filled grains, polylines, caption) as pictures and as the
// frames of an animation. Charts are in render_chart.cpp.
#include "softdrop/render.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "animation_sinks.hpp"
#include "picture_file.hpp"
#include "svg_text.hpp"
#include "util/validation.hpp"

namespace softdrop {
using detail::CairoPtr;
using detail::fail;
using detail::num;
using detail::set;
using detail::show_text;
using detail::SurfacePtr;
using detail::write_picture;

ImageFormat image_format_for(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".svg") return ImageFormat::svg;
  if (ext == ".pdf") return ImageFormat::pdf;
  if (ext == ".gif") return ImageFormat::gif;
  if (ext == ".mp4") return ImageFormat::mp4;
  throw std::invalid_argument("output '" + path +
                              "': unknown picture format (use .png, .svg, .pdf, or .gif / .mp4 for animations)");
}

Rgba parse_colour(const std::string& text) {
  // The '#' is optional: config files (CLI11's TOML reader) take '#' for a comment even in quotes.
  const std::size_t o = !text.empty() && text[0] == '#' ? 1 : 0;
  const auto bad = [&] { return std::invalid_argument("colour '" + text + "': expected #rrggbb or #rrggbbaa"); };
  if (text.size() - o != 6 && text.size() - o != 8) throw bad();
  auto hex = [&](std::size_t i) -> double {
    const std::string two = text.substr(o + i, 2);
    if (!std::isxdigit(static_cast<unsigned char>(two[0])) || !std::isxdigit(static_cast<unsigned char>(two[1])))
      throw bad();
    return std::stoi(two, nullptr, 16) / 255.0;
  };
  return {hex(0), hex(2), hex(4), text.size() - o == 8 ? hex(6) : 1.0};
}

bool RenderStyle::IsValid(std::string* why) const {
  if (width < 16 || width > 10000)
    return fail(why, "size = " + std::to_string(width) + ": must be in [16, 10000] points");
  if (!(dpi >= 36 && dpi <= 1200)) return fail(why, "dpi = " + num(dpi) + ": must be in [36, 1200]");
  if (width * dpi / 72 > 20000)
    return fail(why, "size = " + std::to_string(width) + " at dpi = " + num(dpi) + ": more than 20000 pixels wide");
  if (!std::isfinite(grain_line) || grain_line <= 0)
    return fail(why, "grain-line = " + num(grain_line) + ": must be > 0");
  if (!std::isfinite(margin) || margin < 0) return fail(why, "margin = " + num(margin) + ": must be >= 0");
  return true;
}

namespace {

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
  // A caption's lines are 1.3 font sizes apart, and the last has 1.6 of them.
  const auto lines = static_cast<double>(std::count(scene.caption.begin(), scene.caption.end(), '\n') + 1);
  g.caption_height =
      style.caption && !scene.caption.empty() ? std::max(11.0, 0.02 * style.width) * (1.6 + 1.3 * (lines - 1)) : 0;
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

// A colour map from dark blue through teal and green to yellow (samples of viridis, which reads
// in grey and to colour-blind eyes), linear between its stops.
Rgba colour_map(double t) {
  static constexpr double kStops[][3] = {{0.267, 0.005, 0.329},
                                         {0.231, 0.322, 0.545},
                                         {0.129, 0.569, 0.549},
                                         {0.369, 0.788, 0.384},
                                         {0.993, 0.906, 0.144}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int k = std::min(3, static_cast<int>(t));
  const double f = t - k;
  auto mix = [&](int c) { return kStops[k][c] + f * (kStops[k + 1][c] - kStops[k][c]); };
  return {mix(0), mix(1), mix(2), 1};
}

// The field as an image stretched over the box (x0, y0 its top left on the page, w x h), pixels
// kept square-edged.
void draw_field(cairo_t* cr, const Field& field, double x0, double y0, double w, double h) {
  if (field.values.size() != static_cast<std::size_t>(field.nx) * static_cast<std::size_t>(field.ny))
    throw std::invalid_argument("field: " + std::to_string(field.values.size()) + " values for " +
                                std::to_string(field.nx) + " x " + std::to_string(field.ny) + " pixels");
  SurfacePtr image(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, field.nx, field.ny), cairo_surface_destroy);
  unsigned char* data = cairo_image_surface_get_data(image.get());
  const int stride = cairo_image_surface_get_stride(image.get());
  const double span = field.hi > field.lo ? field.hi - field.lo : 1;
  for (int j = 0; j < field.ny; ++j)
    for (int i = 0; i < field.nx; ++i) {
      const double v = field.values[static_cast<std::size_t>(i + field.nx * j)];
      std::uint32_t pixel = 0;  // transparent
      if (std::isfinite(v)) {
        const Rgba c = colour_map((v - field.lo) / span);
        pixel = 0xff000000u | static_cast<std::uint32_t>(std::lround(255 * c.r)) << 16 |
                static_cast<std::uint32_t>(std::lround(255 * c.g)) << 8 |
                static_cast<std::uint32_t>(std::lround(255 * c.b));
      }
      std::memcpy(data + static_cast<std::ptrdiff_t>(field.ny - 1 - j) * stride + 4 * i, &pixel, 4);
    }
  cairo_surface_mark_dirty(image.get());
  cairo_save(cr);
  cairo_translate(cr, x0, y0);
  cairo_scale(cr, w / field.nx, h / field.ny);
  cairo_set_source_surface(cr, image.get(), 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);
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
  if (scene.field.nx > 0 && scene.field.ny > 0)
    draw_field(cr, scene.field, px(0), py(m.height), g.scale * m.width, g.scale * m.height);
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
  if (const PoreImage* im = m.image.get()) {
    // An image medium: its solid pixels, a rectangle for each run of them along a row.
    // Shifted (a shaken medium), a periodic image is drawn again a width to either side.
    cairo_new_path(cr);
    const double h = im->pixel, sx = scene.image_shift_x, sy = scene.image_shift_y;
    std::vector<double> copies{sx};
    if (m.periodic && sx != 0) copies.push_back(sx - m.width), copies.push_back(sx + m.width);
    for (int j = 0; j < im->ny; ++j)
      for (int i = 0; i < im->nx;) {
        const std::size_t row = static_cast<std::size_t>(im->nx) * static_cast<std::size_t>(j);
        if (im->pore[row + static_cast<std::size_t>(i)]) {
          ++i;
          continue;
        }
        int end = i;
        while (end < im->nx && !im->pore[row + static_cast<std::size_t>(end)]) ++end;
        for (double x : copies)
          cairo_rectangle(cr, px(i * h + x), py((j + 1) * h + sy), g.scale * (end - i) * h, g.scale * h);
        i = end;
      }
    set(cr, style.solid_grains ? style.solid : style.grain);
    cairo_fill(cr);
  }
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
    const double share = i < scene.filled.size() ? std::clamp(scene.filled[i], 0.0, 1.0) : 0.0;
    const bool fill = share > 0;
    if (style.solid_grains && !fill) continue;
    // The least share still shows: a grain one droplet of many touched is not the background.
    Rgba touched = style.touched;
    touched.a *= 0.15 + 0.85 * share;
    for (double x : images(gr)) {
      cairo_new_path(cr);
      cairo_arc(cr, px(x), py(gr.y), g.scale * gr.r, 0, 2 * M_PI);
      if (fill) {
        set(cr, touched);
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
    // Over a halo of the background's colour: a label beside a droplet often lies on a grain.
    const double halo = 0.25 * std::max(9.0, 0.016 * g.width);
    for (const Label& l : scene.labels) {
      set(cr, l.colour);
      cairo_move_to(cr, px(l.x), py(l.y));
      detail::show_text_with_halo(cr, l.text, style.background.r, style.background.g, style.background.b, halo);
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
    // Shrink the font until the caption fits the width. Measured again after each shrink: hinted
    // glyph advances are rounded to whole pixels, so the width is not proportional to the size.
    std::vector<std::string> lines;
    for (std::size_t from = 0;;) {
      const std::size_t to = scene.caption.find('\n', from);
      lines.push_back(scene.caption.substr(from, to == std::string::npos ? std::string::npos : to - from));
      if (to == std::string::npos) break;
      from = to + 1;
    }
    const double base = std::max(11.0, 0.02 * style.width);
    double font = base;
    const double room = g.width - 2 * style.margin;
    cairo_text_extents_t ext;
    for (int tries = 0; tries < 20; ++tries) {
      cairo_set_font_size(cr, font);
      double widest = 0;
      for (const std::string& line : lines) {
        cairo_text_extents(cr, line.c_str(), &ext);
        widest = std::max(widest, ext.x_bearing + ext.width);
      }
      if (widest <= room) break;
      font *= std::min(0.98, room / widest);
    }
    const double bottom = g.height - style.margin - 0.3 * base * 1.6;  // the last line's baseline
    for (std::size_t i = 0; i < lines.size(); ++i) {
      cairo_move_to(cr, style.margin, bottom - 1.3 * base * static_cast<double>(lines.size() - 1 - i));
      show_text(cr, lines[i]);
    }
  }
}

}  // namespace

void render_scene(const Scene& scene, const RenderStyle& style, const std::string& path) {
  std::string why;
  if (!style.IsValid(&why)) throw std::invalid_argument(why);
  if (!scene.medium.IsValid(&why)) throw std::invalid_argument(why);
  const Geometry g = geometry_of(scene, style);
  write_picture(path, g.width, g.height, style.dpi, [&](cairo_t* cr) { draw_scene(cr, scene, style, g); });
}

void render_animation(int frames, double fps, const std::function<void(int, Scene&)>& frame, const RenderStyle& style,
                      const std::string& path) {
  std::string why;
  if (!style.IsValid(&why)) throw std::invalid_argument(why);
  const ImageFormat format = image_format_for(path);
  if (format != ImageFormat::gif && format != ImageFormat::mp4)
    throw std::invalid_argument("output '" + path + "': an animation is written as .gif or .mp4");
  if (frames < 1 || frames > 100000)
    throw std::invalid_argument("frames = " + std::to_string(frames) + ": must be in [1, 1e5]");
  if (!std::isfinite(fps) || fps <= 0 || fps > 100)
    throw std::invalid_argument("fps = " + num(fps) + ": must be in (0, 100]");

  Scene scene;
  frame(0, scene);
  if (!scene.medium.IsValid(&why)) throw std::invalid_argument(why);
  Geometry g = geometry_of(scene, style);  // fixed for all frames
  if (format == ImageFormat::mp4) {        // H.264 wants even sizes: one more row or column of background
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
