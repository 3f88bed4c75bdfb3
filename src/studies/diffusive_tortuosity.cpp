// The diffusive tortuosity of a pore image (pore_tortuosity.hpp): finite volumes on the pixels,
// a sparse Cholesky solve (Eigen's SimplicialLDLT, symmetric positive definite here).
#include <Eigen/Sparse>
#include <cstdint>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "pore_grid.hpp"
#include "pore_tortuosity.hpp"

namespace softdrop {
namespace detail {

std::vector<std::uint8_t> open_pores(const PoreImage& im, bool* joined) {
  const int nx = im.nx, ny = im.ny;
  std::vector<std::uint8_t> from_top(im.pore.size(), 0), open(im.pore.size(), 0);
  auto flood = [&](int row, std::vector<std::uint8_t>& seen) {
    std::deque<std::int64_t> queue;
    for (int i = 0; i < nx; ++i) {
      const auto k = static_cast<std::size_t>(i + nx * row);
      if (im.pore[k] && !seen[k]) seen[k] = 1, queue.push_back(static_cast<std::int64_t>(k));
    }
    while (!queue.empty()) {
      const std::int64_t k = queue.front();
      queue.pop_front();
      const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
      for (int n = 0; n < 4; ++n) {
        const std::int64_t m = face_neighbour(im, i, j, n);
        if (m >= 0 && im.pore[static_cast<std::size_t>(m)] && !seen[static_cast<std::size_t>(m)])
          seen[static_cast<std::size_t>(m)] = 1, queue.push_back(m);
      }
    }
  };
  flood(ny - 1, from_top);
  *joined = false;
  for (int i = 0; i < nx; ++i) *joined = *joined || from_top[static_cast<std::size_t>(i)];
  open = from_top;
  flood(0, open);  // adds the pores joined to the bottom only
  return open;
}

}  // namespace detail

DiffusiveTortuosity diffusive_tortuosity(const PoreImage& image) {
  std::string why;
  if (!image.IsValid(&why)) throw std::invalid_argument(why);
  bool joined = false;
  const std::vector<std::uint8_t> open = detail::open_pores(image, &joined);
  if (!joined) throw std::invalid_argument("image: no pore path from the top to the bottom");
  const int nx = image.nx, ny = image.ny;
  std::vector<std::int64_t> index(image.pore.size(), -1);
  std::int64_t n = 0;
  for (std::size_t k = 0; k < open.size(); ++k)
    if (open[k]) index[k] = n++;
  // Conductance 1 between two pore pixels sharing a face (D (c_a - c_b) / h over a face of h),
  // 2 between a top- or bottom-row pixel and the edge half a pixel away; c = 1 above, 0 below.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int64_t p = index[static_cast<std::size_t>(i + nx * j)];
      if (p < 0) continue;
      double diagonal = 0;
      for (int m = 0; m < 4; ++m) {
        const std::int64_t neighbour = detail::face_neighbour(image, i, j, m);
        if (neighbour < 0) continue;
        const std::int64_t q = index[static_cast<std::size_t>(neighbour)];
        if (q < 0) continue;
        diagonal += 1;
        entries.emplace_back(p, q, -1.0);
      }
      if (j == ny - 1) diagonal += 2, rhs[p] += 2;
      if (j == 0) diagonal += 2;
      entries.emplace_back(p, p, diagonal);
    }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  if (solver.info() != Eigen::Success) throw std::runtime_error("diffusive tortuosity: the solve failed");
  const Eigen::VectorXd c = solver.solve(rhs);
  double flux = 0;  // through the bottom edge
  for (int i = 0; i < nx; ++i)
    if (const std::int64_t p = index[static_cast<std::size_t>(i)]; p >= 0) flux += 2 * c[p];
  DiffusiveTortuosity d;
  d.porosity = image.porosity();
  d.effective_diffusivity = flux * ny / nx;  // flux per width times the height, over the drop of 1
  d.formation_factor = 1 / d.effective_diffusivity;
  d.tau = d.porosity * d.formation_factor;
  d.unknowns = n;
  d.concentration.assign(image.pore.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < index.size(); ++k)
    if (index[k] >= 0) d.concentration[k] = c[index[k]];
  return d;
}

}  // namespace softdrop
