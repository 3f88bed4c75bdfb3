#pragma once
// Text that stays text in SVG files. Cairo's SVG surface writes every glyph as a path, so a
// picture's words could not be searched, selected or edited. Drawing code calls show_text; on a
// context collecting for SVG it records the text (position, size, angle, colour, weight) instead
// of drawing glyphs, and insert_svg_text adds the records to the finished file as <text> elements.
#include <cairo.h>

#include <string>
#include <vector>

namespace softdrop::detail {

struct SvgText {
  double x = 0, y = 0;  // the text's start on its baseline (SVG user units)
  double size = 10;     // font size (SVG user units)
  double angle = 0;     // rotation about (x, y), degrees
  double r = 0, g = 0, b = 0, a = 1;
  bool bold = false;
  double halo = 0;                // width of an outline behind the glyphs (0: none)
  double hr = 1, hg = 1, hb = 1;  // its colour
  std::string text;
};

/// From now on, show_text on `cr` records into `texts` (which must outlive the context).
void collect_svg_text(cairo_t* cr, std::vector<SvgText>* texts);
/// cairo_show_text at the current point, or a record of it on a collecting context.
void show_text(cairo_t* cr, const std::string& text);
/// show_text over an outline `width` wide in the colour (r, g, b) (the background's), so that the
/// words stay readable over grains and paths.
void show_text_with_halo(cairo_t* cr, const std::string& text, double r, double g, double b, double width);
/// Adds `texts` as <text> elements (DejaVu Sans) before the closing </svg> of the file at `path`.
/// Throws std::runtime_error naming the file if it cannot be read or written.
void insert_svg_text(const std::string& path, const std::vector<SvgText>& texts);

}  // namespace softdrop::detail
