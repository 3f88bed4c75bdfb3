// A medium drawn as a binary pore image (pore_tortuosity.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pore_tortuosity.hpp"

namespace softdrop {

bool PoreImage::IsValid(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (nx < 1 || ny < 1) return fail("image: " + std::to_string(nx) + " x " + std::to_string(ny) + " pixels");
  if (!(pixel > 0) || !std::isfinite(pixel)) return fail("pixel size: must be finite and > 0");
  if (pore.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny))
    return fail("image: " + std::to_string(pore.size()) + " values for " + std::to_string(nx) + " x " +
                std::to_string(ny) + " pixels");
  return true;
}

double PoreImage::porosity() const {
  if (pore.empty()) return 0;
  return static_cast<double>(std::count(pore.begin(), pore.end(), std::uint8_t{1})) / static_cast<double>(pore.size());
}

PoreImage pore_image(const Medium& medium, int nx) {
  if (nx < 2) throw std::invalid_argument("pixels = " + std::to_string(nx) + ": must be >= 2 across the box");
  std::string why;
  if (!medium.IsValid(&why)) throw std::invalid_argument(why);
  PoreImage image;
  image.nx = nx;
  image.pixel = medium.width / nx;
  image.periodic = medium.periodic;
  image.ny = std::max(1, static_cast<int>(std::lround(medium.height / image.pixel)));
  if (static_cast<std::int64_t>(image.nx) * image.ny > kMaxPoreImagePixels)
    throw std::invalid_argument("pixels = " + std::to_string(nx) + ": an image of " + std::to_string(image.nx) + " x " +
                                std::to_string(image.ny) + " pixels, more than 6.4e7");
  image.pore.assign(static_cast<std::size_t>(image.nx) * static_cast<std::size_t>(image.ny), 1);
  const double h = image.pixel;
  for (const Grain& g : medium.grains) {
    // The rows and columns whose centres may lie inside the grain; columns wrap in a periodic box.
    const int j0 = std::max(0, static_cast<int>(std::floor((g.y - g.r) / h - 0.5)));
    const int j1 = std::min(image.ny - 1, static_cast<int>(std::ceil((g.y + g.r) / h - 0.5)));
    const int i0 = static_cast<int>(std::floor((g.x - g.r) / h - 0.5));
    const int i1 = static_cast<int>(std::ceil((g.x + g.r) / h - 0.5));
    for (int j = j0; j <= j1; ++j) {
      const double dy = (j + 0.5) * h - g.y;
      for (int i = i0; i <= i1; ++i) {
        int col = i;
        if (image.periodic) {
          col = ((i % nx) + nx) % nx;
        } else if (i < 0 || i >= nx) {
          continue;
        }
        const double dx = (i + 0.5) * h - g.x;
        if (dx * dx + dy * dy < g.r * g.r) image.pore[static_cast<std::size_t>(col + nx * j)] = 0;
      }
    }
  }
  return image;
}

}  // namespace softdrop
