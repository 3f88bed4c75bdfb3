#pragma once
// The signed distance field of an image medium's solid, which the droplet's contact stages read
// in place of the grains: O(1) a look-up, whatever the image. Private to the library.
#include <cstdint>
#include <memory>
#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop {

class DistanceField {
 public:
  /// The field of `image`, built once for each image however many droplets share it (a cache
  /// keyed by the image's owner, kept while the image lives).
  static std::shared_ptr<const DistanceField> of(const std::shared_ptr<const PoreImage>& image);
  explicit DistanceField(const PoreImage& image);

  /// The field at a point, interpolated bilinearly between the pixel centres.
  struct Sample {
    double d = 0;           ///< signed distance to the solid's surface (length units): < 0 inside the solid
    double nx = 0, ny = 1;  ///< the unit normal out of the solid (the gradient of d)
    std::int32_t part = 0;  ///< the solid part nearest, where d < 0 (a connected component of solid pixels)
  };
  /// The field at (x, y), x already wrapped into [0, W) in a periodic medium. False where no solid
  /// is within reach (above and below the image by more than a pixel, or d >= 0 at every pixel
  /// centre around): then the mass touches nothing, and `s` is not written.
  bool sample(double x, double y, Sample* s) const;

  /// Connected parts of the solid (8-neighbour, across the seam of a periodic image): the
  /// touched set's entries.
  std::int32_t parts() const { return parts_; }
  /// A solid part's extent: the sides of the smallest box of pixels that holds it (length units;
  /// a part that wraps around a periodic image is as wide as the box or wider), and its first
  /// pixel (column i, row j from the bottom).
  struct Extent {
    double width = 0, height = 0;
    int i = 0, j = 0;
  };
  const Extent& extent(std::int32_t part) const { return extents_[static_cast<std::size_t>(part)]; }
  /// The field at the centre of the image's pixel (i, j), and its solid part (-1 in the pore).
  double at(int i, int j) const { return d_[index(i, j)]; }
  std::int32_t part_at(int i, int j) const { return part_[index(i, j)]; }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(nx_) * static_cast<std::size_t>(j + kPadding);
  }
  static constexpr int kPadding = 2;  // rows of pore added above and below (distance_field.cpp)
  int nx_ = 0, rows_ = 0;             // columns, and rows with the padding
  double h_ = 1;
  bool periodic_ = true;
  void normals();
  // Floats: 16 bytes a pixel with the parts, and a float's 24 bits place a surface to 1e-7 of the
  // box, far below max_depth.
  std::vector<float> d_;            // at pixel centres, padded rows included (length units)
  std::vector<float> gx_, gy_;      // the gradient of d smoothed, at pixel centres (normals())
  std::vector<std::int32_t> part_;  // per padded pixel: its solid part, -1 in pore
  std::int32_t parts_ = 0;
  std::vector<Extent> extents_;  // per part
};

}  // namespace softdrop
