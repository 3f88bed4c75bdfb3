#pragma once
// A picture written whole (internal to the drawing module): Cairo's handles, and the one routine
// that paints onto a PNG, SVG or PDF surface and renames the finished file over its path.
#include <cairo.h>

#include <functional>
#include <memory>
#include <string>

#include "softdrop/render.hpp"

namespace softdrop::detail {

using CairoPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;
using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

inline void set(cairo_t* cr, const Rgba& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

// Draws with `paint(cr)` (in points: 1/72 inch) on a surface of the format of `path`, `width` x
// `height` points, PNG at `dpi`, into a temporary file renamed over `path` on success. Throws
// std::invalid_argument for a format that is not a still picture and std::runtime_error naming
// `path` if Cairo or the file system fails; no file is then left at `path` or beside it.
void write_picture(const std::string& path, int width, int height, double dpi,
                   const std::function<void(cairo_t*)>& paint);

}  // namespace softdrop::detail
