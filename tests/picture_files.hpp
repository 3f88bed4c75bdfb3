#pragma once
// Reading the pictures the tests draw: a PNG's size, pixels and resolution, and an SVG's styled
// elements.

#include <cairo.h>
#include <tinyxml2.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace softdrop::test {

struct Png {
  int width = 0, height = 0;
  long non_background = 0;  // pixels that differ from the top-left one
};

// The size of a PNG and how many of its pixels differ from the top-left one (all 0 if unreadable).
inline Png read_png(const std::string& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  Png p;
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    p.width = cairo_image_surface_get_width(s);
    p.height = cairo_image_surface_get_height(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    const int stride = cairo_image_surface_get_stride(s);
    const auto background = *reinterpret_cast<const std::uint32_t*>(data);
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x)
        p.non_background += reinterpret_cast<const std::uint32_t*>(data + y * stride)[x] != background;
  }
  cairo_surface_destroy(s);
  return p;
}

// The pixels of a PNG, row by row.
inline std::vector<std::uint32_t> png_pixels(const std::string& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  std::vector<std::uint32_t> out;
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    const unsigned char* data = cairo_image_surface_get_data(s);
    const int stride = cairo_image_surface_get_stride(s);
    for (int y = 0; y < cairo_image_surface_get_height(s); ++y)
      for (int x = 0; x < cairo_image_surface_get_width(s); ++x)
        out.push_back(reinterpret_cast<const std::uint32_t*>(data + y * stride)[x]);
  }
  cairo_surface_destroy(s);
  return out;
}

// The resolution a PNG's pHYs chunk gives, in pixels an inch (0: no chunk, or not in metres).
inline double png_dpi(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  for (std::size_t at = 8; at + 8 <= bytes.size();) {  // chunks after the 8-byte signature
    const std::uint32_t length = be32(at);
    if (bytes.compare(at + 4, 4, "pHYs") == 0 && length == 9 && bytes[at + 16] == 1) return be32(at + 8) * 0.0254;
    at += 12 + length;
  }
  return 0;
}

// Elements anywhere below `e` whose attribute `style` contains `needle`.
inline int count_styled(const tinyxml2::XMLElement* e, const std::string& needle) {
  int n = 0;
  for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const char* style = c->Attribute("style");
    if (style && std::string(style).find(needle) != std::string::npos) ++n;
    n += count_styled(c, needle);
  }
  return n;
}

}  // namespace softdrop::test
