#pragma once
// A Cairo image surface written as a PNG through libpng, with its resolution: a pHYs chunk of
// `dpi` pixels an inch, so that a viewer or a typesetter prints it at the size it was drawn for
// (Cairo's own writer leaves the chunk out, and such a file reads as 72 dpi).
#include <cairo.h>

#include <string>

namespace softdrop::detail {

// Writes `surface` (CAIRO_FORMAT_ARGB32) to `path` as 8-bit RGB if every pixel is opaque, RGBA
// otherwise. Throws std::runtime_error with
// libpng's or the system's reason; `path` may then hold part of a file (callers write a temporary
// name and rename it).
void write_png(cairo_surface_t* surface, const std::string& path, double dpi);

}  // namespace softdrop::detail
