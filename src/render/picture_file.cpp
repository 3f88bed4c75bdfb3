#include "picture_file.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "png_file.hpp"
#include "svg_text.hpp"
#include "util/temp_files.hpp"

namespace softdrop::detail {

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
    case ImageFormat::svg:
      raw = cairo_svg_surface_create(tmp.c_str(), width, height);
      break;
    case ImageFormat::pdf:
      raw = cairo_pdf_surface_create(tmp.c_str(), width, height);
      break;
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
    try {
      write_png(surface.get(), tmp, dpi);
    } catch (const std::runtime_error& e) {
      throw failed(e.what());
    }
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

}  // namespace softdrop::detail
