#pragma once
// Pore images with known answers, shared by the pore-space tests.
#include <cmath>
#include <cstddef>

#include "studies/pore_tortuosity.hpp"

namespace softdrop::test {

// n x n pixels of side `pixel`: pore where (x - s y) mod period < width, x and y at the pixel's
// centre in pixels: channels at slope s (x rises by s a pixel of y). With n s a multiple of the
// period the image is periodic in y too.
inline PoreImage slanted_channels(int n, double s, int period, int width, double pixel = 1) {
  PoreImage im;
  im.nx = im.ny = n;
  im.pixel = pixel;
  im.pore.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double u = std::fmod(i + 0.5 - s * (j + 0.5), static_cast<double>(period));
      if (u < 0) u += period;
      im.pore[static_cast<std::size_t>(i + n * j)] = u < width;
    }
  return im;
}

}  // namespace softdrop::test
