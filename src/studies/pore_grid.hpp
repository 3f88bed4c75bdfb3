#pragma once
// The face neighbours of a pixel of a pore image (pore_tortuosity.hpp), shared by its solves.
// Internal to softdrop_studies.
#include <cstdint>
#include <vector>

#include "pore_tortuosity.hpp"

namespace softdrop::detail {

// The index of pixel (i, j)'s neighbour n (0: left, 1: right, 2: below, 3: above), wrapping in x
// in a periodic image; -1 past the top, the bottom, or a wall.
inline std::int64_t face_neighbour(const PoreImage& im, int i, int j, int n) {
  int ii = i + (n == 0 ? -1 : n == 1 ? 1 : 0);
  const int jj = j + (n == 2 ? -1 : n == 3 ? 1 : 0);
  if (jj < 0 || jj >= im.ny) return -1;
  if (ii < 0 || ii >= im.nx) {
    if (!im.periodic) return -1;
    ii = (ii + im.nx) % im.nx;
  }
  return ii + static_cast<std::int64_t>(im.nx) * jj;
}

// The pore pixels joined through pore faces (periodic in x if the image is) to the top or the
// bottom row: the others are closed pockets, which carry no flux and would leave a solve
// singular. `*joined`: whether a pore path joins the top row to the bottom row.
std::vector<std::uint8_t> open_pores(const PoreImage& im, bool* joined);

}  // namespace softdrop::detail
