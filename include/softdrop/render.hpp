#pragma once
/// \file render.hpp
/// Pictures of media, droplets, paths and searches, drawn with Cairo: PNG, SVG and PDF from the
/// same drawing code (chosen by the file extension), and animations as GIF (giflib) or MP4 (ffmpeg).
/// One module shared by the CLI, the studies and the tests. Files are written atomically.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop {

/// Output format, from the file extension.
enum class ImageFormat { png, svg, pdf, gif, mp4 };
/// .png, .svg, .pdf, .gif or .mp4 (case-insensitive); throws std::invalid_argument naming the path.
ImageFormat image_format_for(const std::string& path);

/// A colour with alpha, components in [0, 1].
struct Rgba {
  double r = 0, g = 0, b = 0, a = 1;
  bool operator==(const Rgba&) const = default;
};
/// Parses "#rrggbb" or "#rrggbbaa" (the "#" may be left out); throws std::invalid_argument naming
/// the text.
Rgba parse_colour(const std::string& text);

/// How pictures look. Lengths are in output pixels (points for SVG and PDF).
struct RenderStyle {
  int width = 800;  ///< picture width in points (1/72 inch); the height follows
  /// PNG resolution: a PNG is width * dpi / 72 pixels wide, drawn the same (SVG and PDF are
  /// resolution-free). 72: a pixel a point; 300 for print.
  double dpi = 72;
  Rgba background{1, 1, 1, 1};
  Rgba grain{0.12, 0.16, 0.22, 1};    ///< grain outlines ("wire spheres")
  Rgba touched{0.25, 0.27, 0.30, 1};  ///< fill of grains the droplet touched
  Rgba box{0.55, 0.55, 0.55, 1};      ///< the medium's box
  Rgba text{0, 0, 0, 1};
  double grain_line = 1.2;
  /// Draw the grains as one solid region, the union of the discs in `solid` (touched ones in
  /// `touched`), not as outlines: for overlapping grains, whose outlines would cross inside solid.
  bool solid_grains = false;
  Rgba solid{0.70, 0.73, 0.78, 1};
  double margin = 12;
  bool caption = true;     ///< the scene's caption under the picture
  bool scale_bar = false;  ///< a bar of a round length, labelled, at the box's lower left

  bool IsValid(std::string* why) const;
};

/// A polyline in medium coordinates (y up): a path, or a droplet's boundary (closed).
struct Polyline {
  std::vector<double> x, y;
  Rgba colour{0.8, 0.1, 0.1, 1};
  double width = 2;       ///< line width (pixels)
  bool closed = false;    ///< join the last point to the first
  Rgba fill{0, 0, 0, 0};  ///< fill of a closed polyline (alpha 0: none)
};

/// What to draw: a medium, grains to fill, polylines on top, a caption.
/// A short text at a point of the medium (its left end; medium coordinates, y up).
struct Label {
  double x = 0, y = 0;
  std::string text;
  Rgba colour{0, 0, 0, 1};
};

/// A scalar field over the medium's box on a pixel grid, drawn under the grains in a colour map
/// from `lo` (dark blue) to `hi` (yellow); NaN pixels are left to the background.
struct Field {
  int nx = 0, ny = 0;
  std::vector<double> values;  ///< nx * ny, rows from the bottom (y = 0) up
  double lo = 0, hi = 1;
};

struct Scene {
  Medium medium;
  Field field;  ///< optional, under everything else
  /// Per grain, how strongly it is filled in RenderStyle::touched, from 0 (not filled) to 1: 1 for
  /// a grain that one droplet touched; among many droplets, the share of them that touched it
  /// (any share above 0 is drawn at least faintly).
  std::vector<double> filled;
  std::vector<Polyline> lines;
  std::vector<Label> labels;  ///< drawn on top of everything in the box
  std::string caption;        ///< under the picture; "\n" starts another line
  /// Extra room above the medium (length units) so that droplets starting above it are seen;
  /// -1: fit the polylines.
  double top_room = -1;
  /// An image medium's pixels are drawn moved by this (length units): a shaken medium as it
  /// moves (a grain medium's grains are moved in `medium` itself). Periodic in x as the medium is.
  double image_shift_x = 0, image_shift_y = 0;
};

/// Draws a scene to a PNG, SVG or PDF file (by extension). With a periodic medium, grains that
/// cross x = 0 or x = W are drawn again at their periodic image, and polylines are wrapped into
/// [0, W). Throws std::runtime_error naming the file on failure; nothing is left half-written.
void render_scene(const Scene& scene, const RenderStyle& style, const std::string& path);

/// One data series of a chart.
struct Series {
  enum class Style { line, steps, points };
  std::vector<double> x, y;
  std::vector<double> err;  ///< optional y error bars (same length as y)
  std::string label;        ///< legend entry (empty: none)
  Style style = Style::line;
  Rgba colour{0.8, 0.1, 0.1, 1};
  double width = 2;  ///< line width, or point radius for points
};

/// A chart: series, vertical markers, axes with ticks and labels, a legend.
struct Chart {
  std::vector<Series> series;
  std::vector<double> markers;             ///< vertical dashed lines at these x
  std::vector<std::string> marker_labels;  ///< their labels (optional)
  std::vector<double> hlines;              ///< horizontal dotted lines at these y
  std::string x_label, y_label, title;
};
/// Draws a chart to a PNG, SVG or PDF file; height = 0.62 width. Axes span all series (with error
/// bars) and markers. Throws std::invalid_argument for an empty chart or mismatched lengths.
void render_chart(const Chart& chart, const RenderStyle& style, const std::string& path);

/// An animation: frame(i, scene) fills the scene of frame i for i in [0, frames); frames are
/// drawn as for render_scene at `fps` frames per second and encoded by the extension: .gif with
/// giflib (a fixed 256-colour palette, looping) or .mp4 with the ffmpeg program (H.264, yuv420p).
/// Throws std::runtime_error naming the file on failure (ffmpeg missing included).
void render_animation(int frames, double fps, const std::function<void(int, Scene&)>& frame, const RenderStyle& style,
                      const std::string& path);

}  // namespace softdrop
