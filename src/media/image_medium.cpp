// Image media: a binary pore image as a medium (softdrop/medium.hpp).
#include "media/image_medium.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "util/validation.hpp"

namespace softdrop {
using detail::fail;
using detail::num;

bool PoreImage::IsValid(std::string* why) const {
  if (nx < 1 || ny < 1) return fail(why, "image: " + std::to_string(nx) + " x " + std::to_string(ny) + " pixels");
  if (!(pixel > 0) || !std::isfinite(pixel))
    return fail(why, "pixel size = " + num(pixel) + ": must be finite and > 0");
  if (pore.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny))
    return fail(why, "image: " + std::to_string(pore.size()) + " values for " + std::to_string(nx) + " x " +
                         std::to_string(ny) + " pixels");
  if (std::any_of(pore.begin(), pore.end(), [](std::uint8_t v) { return v > 1; }))
    return fail(why, "image: not binary (a value other than 0 and 1)");
  return true;
}

double PoreImage::porosity() const {
  if (pore.empty()) return 0;
  return static_cast<double>(std::count(pore.begin(), pore.end(), std::uint8_t{1})) / static_cast<double>(pore.size());
}

namespace detail {
bool image_is_valid(const Medium& m, std::string* why) {
  if (!m.image->IsValid(why)) return false;
  if (!m.grains.empty()) return fail(why, "an image medium has no grains");
  const PoreImage& im = *m.image;
  if (m.width != im.nx * im.pixel || m.height != im.ny * im.pixel)
    return fail(why, "width and height: must be the image's, " + num(im.nx * im.pixel) + " x " + num(im.ny * im.pixel));
  if (m.periodic != im.periodic) return fail(why, "periodic: must be the image's");
  return true;
}
}  // namespace detail

bool Medium::operator==(const Medium& o) const {
  if (width != o.width || height != o.height || periodic != o.periodic || grains != o.grains) return false;
  if (!image || !o.image) return !image && !o.image;
  return image == o.image || *image == *o.image;
}

Medium image_medium(PoreImage image) {
  if (image.pixel > kMaxBoxSide / std::max(1, std::max(image.nx, image.ny)))
    throw std::invalid_argument("pixel size = " + num(image.pixel) + ": the box would be wider than 1e9");
  std::string why;
  if (!image.IsValid(&why)) throw std::invalid_argument(why);
  if (std::find(image.pore.begin(), image.pore.end(), std::uint8_t{1}) == image.pore.end())
    throw std::invalid_argument("image: no pore pixel (white, 1 or True is pore)");
  Medium m;
  m.width = image.nx * image.pixel;
  m.height = image.ny * image.pixel;
  m.periodic = image.periodic;
  m.image = std::make_shared<const PoreImage>(std::move(image));
  return m;
}

namespace detail {
std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}
}  // namespace detail

bool is_image_file(const std::string& path) {
  const std::string e = detail::lower_extension(path);
  return e == ".png" || e == ".tif" || e == ".tiff" || e == ".npy";
}

Medium load_image_medium(const std::string& path, double pixel, bool periodic) {
  if (!(pixel > 0) || !std::isfinite(pixel))
    throw std::invalid_argument("pixel size = " + num(pixel) + ": must be finite and > 0");
  PoreImage image = detail::read_image_file(path);
  image.pixel = pixel;
  image.periodic = periodic;
  try {
    return image_medium(std::move(image));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("image '" + path + "': " + e.what());
  }
}

void save_image_medium(const std::string& path, const Medium& medium) {
  if (!medium.image) throw std::invalid_argument(path + ": a medium of grains is saved as a grain file (.json, .csv)");
  const std::string e = detail::lower_extension(path);
  if (e != ".png" && e != ".npy") throw std::invalid_argument(path + ": an image medium is saved as .png or .npy");
  write_file_atomically(path, detail::image_file_bytes(path, *medium.image));
}

}  // namespace softdrop
