#pragma once
/// \file grain_grid.hpp
/// A uniform grid over a medium that lists, for each cell, every grain overlapping the cell (or
/// coming within a chosen halo of it), so a point's contacts are found by looking in one cell: O(1)
/// per mass, whatever the grain count.

#include <cstdint>
#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop {

class GrainGrid {
 public:
  /// Builds the grid; periodic media get the images of grains that cross x = 0 or x = W.
  /// `cell_size` <= 0 picks the mean grain diameter. `halo_cells` >= 0, a fraction of the cell
  /// side: a cell also lists the grains that come within that distance of it, which lets a point
  /// move further before a grain outside its cell's list could reach it (edge_distance()).
  explicit GrainGrid(const Medium& medium, double cell_size = 0, double halo_cells = 0);

  /// Grains (as indices into the stored arrays, in increasing order) whose disc may contain points
  /// of the cell holding (x, y) or come within the halo of it; x must already be wrapped into
  /// [0, W) for periodic media. Empty outside the grid. The discs that contain a point are listed
  /// in the same order whatever the cell size and halo.
  struct Range {
    const std::int32_t* begin;
    const std::int32_t* end;
  };
  Range query(double x, double y) const {
    const std::int64_t c = cell_of(x, y);
    if (c < 0) return {nullptr, nullptr};
    return {items_.data() + start_[c], items_.data() + start_[c + 1]};
  }
  /// The cell holding (x, y), -1 outside the grid (or for NaN).
  std::int64_t cell_of(double x, double y) const {
    const double fx = (x - x0_) * inv_cell_;
    const double fy = (y - y0_) * inv_cell_;
    if (!(fx >= 0 && fy >= 0 && fx < nx_ && fy < ny_)) return -1;
    return static_cast<std::int64_t>(fy) * nx_ + static_cast<std::int64_t>(fx);
  }

  /// A stored disc as listed in a cell: its copy in the cell's own run of entries, so that the
  /// simulator's contact loops read one contiguous block per mass instead of following indices.
  struct Disc {
    double x, y, r;
    std::int32_t grain;  ///< index of the medium grain (an image maps to its original)
  };
  struct DiscRange {
    const Disc* begin;
    const Disc* end;
  };
  /// The same discs as query(x, y), as copies.
  DiscRange discs_near(double x, double y) const { return discs_in(cell_of(x, y)); }
  /// The discs of cell c (from cell_of); none for -1.
  DiscRange discs_in(std::int64_t c) const {
    if (c < 0) return {nullptr, nullptr};
    return {discs_.data() + start_[c], discs_.data() + start_[c + 1]};
  }

  /// How far from (x, y) a disc not listed in its cell must be: the distance to the nearest edge of
  /// its cell plus the halo (a disc not listed comes no nearer to the cell than the halo), or,
  /// outside the grid, the distance to the grid, which holds every disc (length; NaN for NaN).
  double edge_distance(double x, double y) const;

  /// Stored discs (grains and their periodic images), flat arrays.
  const std::vector<double>& gx() const { return gx_; }
  const std::vector<double>& gy() const { return gy_; }
  const std::vector<double>& gr() const { return gr_; }
  /// Index of the medium grain a stored disc is (an image maps to its original).
  const std::vector<std::int32_t>& grain_id() const { return id_; }
  double cell_size() const { return 1.0 / inv_cell_; }
  /// The halo as a length (halo_cells times the cell side).
  double halo() const { return halo_; }
  /// Grain entries over all cells (a disc overlapping k cells counts k times): the grid's size,
  /// kept at most 64 per stored disc (plus 4096) by coarsening the cells when needed.
  std::size_t entries() const { return items_.size(); }
  /// The most entries any one cell lists: at most this many discs are near a point.
  std::size_t max_cell_entries() const { return max_cell_; }

 private:
  double x0_ = 0, y0_ = 0, inv_cell_ = 1, halo_ = 0;
  int nx_ = 0, ny_ = 0;
  std::size_t max_cell_ = 0;
  std::vector<std::int64_t> start_;
  std::vector<std::int32_t> items_;
  std::vector<Disc> discs_;  ///< items_ with the discs' data, entry for entry
  std::vector<double> gx_, gy_, gr_;
  std::vector<std::int32_t> id_;
};

}  // namespace softdrop
