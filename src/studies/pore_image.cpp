// A medium drawn as a binary pore image (pore_tortuosity.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pore_tortuosity.hpp"

namespace softdrop {

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
  if (const PoreImage* source = medium.image.get()) {
    // An image medium: each pixel takes the source pixel its centre falls in.
    for (int j = 0; j < image.ny; ++j) {
      const int sj = std::min(source->ny - 1, static_cast<int>((j + 0.5) * h / source->pixel));
      for (int i = 0; i < image.nx; ++i) {
        const int si = std::min(source->nx - 1, static_cast<int>((i + 0.5) * h / source->pixel));
        image.pore[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * static_cast<std::size_t>(j)] =
            source->pore[static_cast<std::size_t>(si) +
                         static_cast<std::size_t>(source->nx) * static_cast<std::size_t>(sj)];
      }
    }
    return image;
  }
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
