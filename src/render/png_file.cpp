#include "png_file.hpp"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace softdrop::detail {
namespace {

// Whether every pixel is opaque: the file is then RGB, a quarter smaller, as Cairo's writer does.
bool opaque(const unsigned char* data, int width, int height, int stride) {
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t p = 0;
      std::memcpy(&p, data + static_cast<std::ptrdiff_t>(y) * stride + 4 * x, 4);
      if ((p >> 24) != 255) return false;
    }
  return true;
}

// Cairo's ARGB32 pixels (premultiplied alpha, native-endian 32-bit words) as straight RGBA bytes,
// or RGB when `channels` is 3, unpremultiplied as Cairo's own PNG writer does.
void to_bytes(const unsigned char* row, int width, int channels, unsigned char* out) {
  for (int x = 0; x < width; ++x) {
    std::uint32_t p = 0;
    std::memcpy(&p, row + 4 * x, 4);
    const unsigned a = p >> 24;
    unsigned r = (p >> 16) & 0xff, g = (p >> 8) & 0xff, b = p & 0xff;
    if (a != 0 && a != 255) {
      r = (r * 255 + a / 2) / a;
      g = (g * 255 + a / 2) / a;
      b = (b * 255 + a / 2) / a;
    }
    unsigned char* o = out + channels * x;
    o[0] = static_cast<unsigned char>(r), o[1] = static_cast<unsigned char>(g);
    o[2] = static_cast<unsigned char>(b);
    if (channels == 4) o[3] = static_cast<unsigned char>(a);
  }
}

struct Writer {
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::FILE* file = nullptr;
  char message[256] = "";
  ~Writer() {
    png_destroy_write_struct(&png, &info);
    if (file) std::fclose(file);
  }
};

// libpng reports an error by calling this and then jumping back to the setjmp in write_rows.
void on_error(png_structp png, png_const_charp what) {
  auto* w = static_cast<Writer*>(png_get_error_ptr(png));
  std::snprintf(w->message, sizeof w->message, "%s", what);
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

// The libpng calls, with no C++ object made between the setjmp and a jump back to it.
bool write_rows(Writer& w, int width, int height, int colour_type, std::uint32_t pixels_per_metre, png_bytepp rows) {
  if (setjmp(png_jmpbuf(w.png))) return false;
  png_init_io(w.png, w.file);
  png_set_IHDR(w.png, w.info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, colour_type,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_pHYs(w.png, w.info, pixels_per_metre, pixels_per_metre, PNG_RESOLUTION_METER);
  png_write_info(w.png, w.info);
  png_write_image(w.png, rows);
  png_write_end(w.png, w.info);
  return true;
}

}  // namespace

void write_png(cairo_surface_t* surface, const std::string& path, double dpi) {
  cairo_surface_flush(surface);
  const int width = cairo_image_surface_get_width(surface), height = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  if (!data || cairo_image_surface_get_format(surface) != CAIRO_FORMAT_ARGB32)
    throw std::runtime_error("not an ARGB32 image surface");
  const int channels = opaque(data, width, height, stride) ? 3 : 4;
  const std::size_t row_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  std::vector<unsigned char> bytes(row_bytes * static_cast<std::size_t>(height));
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    rows[static_cast<std::size_t>(y)] = bytes.data() + static_cast<std::size_t>(y) * row_bytes;
    to_bytes(data + static_cast<std::ptrdiff_t>(y) * stride, width, channels, rows[static_cast<std::size_t>(y)]);
  }
  Writer w;
  w.file = std::fopen(path.c_str(), "wb");
  if (!w.file) throw std::runtime_error(std::strerror(errno));
  w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w, on_error, on_warning);
  if (w.png) w.info = png_create_info_struct(w.png);
  if (!w.png || !w.info) throw std::runtime_error("libpng: out of memory");
  // 1 inch = 0.0254 m.
  const auto ppm = static_cast<std::uint32_t>(std::lround(dpi / 0.0254));
  if (!write_rows(w, width, height, channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA, ppm, rows.data()))
    throw std::runtime_error(std::string("libpng: ") + w.message);
  const bool closed = std::fclose(w.file) == 0;
  w.file = nullptr;
  if (!closed) throw std::runtime_error(std::strerror(errno));
}

}  // namespace softdrop::detail
