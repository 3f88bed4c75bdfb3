// The hydrodynamic tortuosity and the permeability of a pore image (pore_tortuosity.hpp): creeping
// flow on a staggered (MAC) grid, the velocities on the pixels' faces and the pressure at their
// centres, solved by conjugate gradients on the pressure's Schur complement with the two velocity
// Laplacians factored once (CHOLMOD's supernodal Cholesky, through Eigen: on a 500 x 500 image it
// factors in a quarter of the time of Eigen's own simplicial one): Uzawa's method, exact to the
// tolerance, in about a dozen iterations.
#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "pore_grid.hpp"
#include "pore_tortuosity.hpp"

namespace softdrop {
namespace {

using Index = std::int64_t;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::SparseMatrix<double>;

// The box the flow is solved in: the image with `buffer` rows of open fluid above and below it,
// periodic in y (and in x if the image is). Cell (i, j) is pixel (i, j - buffer) of the image.
struct Box {
  int nx = 0, ny = 0, buffer = 0;
  bool periodic_x = true;
  std::vector<std::uint8_t> fluid;  // after closed pockets are removed
  Index cell(int i, int j) const { return i + static_cast<Index>(nx) * j; }
  int wrap_y(int j) const { return (j % ny + ny) % ny; }
  // The cell left of column i (-1 past a wall).
  int left(int i) const { return i > 0 ? i - 1 : periodic_x ? nx - 1 : -1; }
  int right(int i) const { return i < nx - 1 ? i + 1 : periodic_x ? 0 : -1; }
  bool is_fluid(int i, int j) const { return i >= 0 && fluid[static_cast<std::size_t>(cell(i, wrap_y(j)))]; }
  bool in_medium(int j) const { return j >= buffer && j < ny - buffer; }
};

Box make_box(const PoreImage& image, int buffer) {
  Box b;
  b.nx = image.nx, b.ny = image.ny + 2 * buffer, b.buffer = buffer, b.periodic_x = image.periodic;
  b.fluid.assign(static_cast<std::size_t>(b.nx) * static_cast<std::size_t>(b.ny), 1);
  for (int j = 0; j < image.ny; ++j)
    for (int i = 0; i < image.nx; ++i)
      b.fluid[static_cast<std::size_t>(b.cell(i, j + buffer))] = image.pore[static_cast<std::size_t>(i + image.nx * j)];
  // Keep the cells joined through fluid faces to the bottom row (with a buffer, every cell joined
  // to the open fluid): closed pockets carry no flow and would leave the pressure undetermined.
  std::vector<std::uint8_t> seen(b.fluid.size(), 0);
  std::deque<std::pair<int, int>> queue;
  for (int i = 0; i < b.nx; ++i)
    if (b.is_fluid(i, 0)) seen[static_cast<std::size_t>(b.cell(i, 0))] = 1, queue.emplace_back(i, 0);
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    const std::pair<int, int> next[] = {{b.left(i), j}, {b.right(i), j}, {i, b.wrap_y(j - 1)}, {i, b.wrap_y(j + 1)}};
    for (const auto& [ii, jj] : next)
      if (b.is_fluid(ii, jj) && !seen[static_cast<std::size_t>(b.cell(ii, jj))])
        seen[static_cast<std::size_t>(b.cell(ii, jj))] = 1, queue.emplace_back(ii, jj);
  }
  b.fluid = seen;
  return b;
}

// The unknowns: u on the face left of cell (i, j), v on the face below it, each where both cells
// beside the face are fluid; p at each fluid cell. -1: none (a wall, or solid).
struct Unknowns {
  std::vector<Index> u, v, p;
  Index nu = 0, nv = 0, np = 0;
};

Unknowns number(const Box& b) {
  Unknowns n;
  const std::size_t cells = b.fluid.size();
  n.u.assign(cells, -1), n.v.assign(cells, -1), n.p.assign(cells, -1);
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i) {
      const auto k = static_cast<std::size_t>(b.cell(i, j));
      if (!b.fluid[k]) continue;
      n.p[k] = n.np++;
      if (b.is_fluid(b.left(i), j)) n.u[k] = n.nu++;
      if (b.is_fluid(i, j - 1)) n.v[k] = n.nv++;
    }
  return n;
}

// -Laplacian of one velocity component, with unit pixels and viscosity: a neighbour face that is
// an unknown couples; one across the flow (normal to the component) that is not lies on a solid
// cell's face, where the velocity is 0; one along a wall (tangential) has the wall half a pixel
// away, no slip: twice the coupling to 0.
Matrix laplacian(const Box& b, const std::vector<Index>& face, Index n, bool is_u) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(5 * n));
  auto at = [&](int i, int j) -> Index {
    if (i < 0) return -1;
    return face[static_cast<std::size_t>(b.cell(i, b.wrap_y(j)))];
  };
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i) {
      const Index r = face[static_cast<std::size_t>(b.cell(i, j))];
      if (r < 0) continue;
      double diagonal = 0;
      // Along the component (u: left and right; v: below and above): a missing face is on a solid
      // cell's far side, at one pixel, velocity 0.
      const Index along[] = {is_u ? at(b.left(i), j) : at(i, j - 1), is_u ? at(b.right(i), j) : at(i, j + 1)};
      for (const Index c : along) {
        diagonal += 1;
        if (c >= 0) t.emplace_back(r, c, -1.0);
      }
      // Across it: a missing face means a wall half a pixel away.
      const Index across[] = {is_u ? at(i, j - 1) : at(b.left(i), j), is_u ? at(i, j + 1) : at(b.right(i), j)};
      for (const Index c : across) {
        diagonal += c >= 0 ? 1 : 2;
        if (c >= 0) t.emplace_back(r, c, -1.0);
      }
      t.emplace_back(r, r, diagonal);
    }
  Matrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

// The divergence, cells x faces (the u block, then the v block): a cell's outflow through its
// right and top faces minus its inflow through its left and bottom ones.
Matrix divergence(const Box& b, const Unknowns& n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i) {
      const auto k = static_cast<std::size_t>(b.cell(i, j));
      const Index r = n.p[k];
      if (r < 0) continue;
      if (n.u[k] >= 0) t.emplace_back(r, n.u[k], -1.0);
      if (const int ri = b.right(i); ri >= 0) {
        const Index f = n.u[static_cast<std::size_t>(b.cell(ri, j))];
        if (f >= 0) t.emplace_back(r, f, 1.0);
      }
      if (n.v[k] >= 0) t.emplace_back(r, n.nu + n.v[k], -1.0);
      const Index f = n.v[static_cast<std::size_t>(b.cell(i, b.wrap_y(j + 1)))];
      if (f >= 0) t.emplace_back(r, n.nu + f, 1.0);
    }
  Matrix d(n.np, n.nu + n.nv);
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

// CHOLMOD's supernodes go through the BLAS. OpenBLAS, when it is the BLAS, splits them over
// threads by the machine's core count, which may change the last bits; one thread keeps the flow
// the same to the bit on every machine (the reference BLAS has one anyway).
void one_blas_thread() {
  using SetThreads = void (*)(int);
  static const bool once = [] {
    if (void* f = ::dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) reinterpret_cast<SetThreads>(f)(1);
    return true;
  }();
  (void)once;
}

}  // namespace

HydrodynamicTortuosity hydrodynamic_tortuosity(const PoreImage& image, const FlowOptions& options) {
  std::string why;
  if (!image.IsValid(&why)) throw std::invalid_argument(why);
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  bool joined = false;  // inside the image, not around through the buffers
  (void)detail::open_pores(image, &joined);
  if (!joined) throw std::invalid_argument("image: no pore path from the top to the bottom");
  const int buffer = options.buffer_rows >= 0 ? options.buffer_rows : std::max(4, image.ny / 25);
  HydrodynamicTortuosity out;
  out.buffer_rows = buffer;
  out.porosity = image.porosity();
  const std::size_t pixels = image.pore.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.ux.assign(pixels, nan), out.uy.assign(pixels, nan), out.pressure.assign(pixels, nan);
  if (std::count(image.pore.begin(), image.pore.end(), std::uint8_t{0}) == 0 && image.periodic) {
    // Nothing holds the fluid back: plug flow, straight down, without limit.
    out.tortuosity = 1;
    out.permeability = std::numeric_limits<double>::infinity();
    return out;
  }
  const Box b = make_box(image, buffer);
  const Unknowns n = number(b);
  const Matrix d = divergence(b, n);
  one_blas_thread();
  const Matrix a_u = laplacian(b, n.u, n.nu, true), a_v = laplacian(b, n.v, n.nv, false);
  Eigen::CholmodSupernodalLLT<Matrix> solve_u, solve_v;
  if (n.nu > 0) solve_u.compute(a_u);
  if (n.nv > 0) solve_v.compute(a_v);
  if ((n.nu > 0 && solve_u.info() != Eigen::Success) || (n.nv > 0 && solve_v.info() != Eigen::Success))
    throw std::runtime_error("hydrodynamic tortuosity: the velocity solve failed");
  const auto inverse_a = [&](const Vector& g) {  // A^-1 g, block by block
    Vector w(n.nu + n.nv);
    if (n.nu > 0) w.head(n.nu) = solve_u.solve(g.head(n.nu));
    if (n.nv > 0) w.tail(n.nv) = solve_v.solve(g.tail(n.nv));
    return w;
  };
  // The force: 1 along -y on the faces of the image's rows and its top and bottom edges, ny + 1
  // pixels between the centres of the buffer rows beside it (the buffers are driven only by the
  // pressure, whose drop across the image enters Darcy's law below), in units of f h.
  Vector f = Vector::Zero(n.nu + n.nv);
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i)
      if (const Index k = n.v[static_cast<std::size_t>(b.cell(i, j))]; k >= 0 && (b.in_medium(j) || b.in_medium(j - 1)))
        f[n.nu + k] = -1;
  // A u - D^T p = f and D u = 0: the pressure solves D A^-1 D^T p = -D A^-1 f, symmetric positive
  // semidefinite (constants are its null space, projected out), by conjugate gradients.
  const auto project = [](Vector& x) { x.array() -= x.mean(); };
  const auto schur = [&](const Vector& p) { return Vector(d * inverse_a(d.transpose() * p)); };
  Vector rhs = -(d * inverse_a(f));
  project(rhs);
  Vector p = Vector::Zero(n.np), r = rhs, s = r;
  const double target = options.tolerance * rhs.norm();
  double rr = r.squaredNorm();
  int iteration = 0;
  for (; iteration < options.max_iterations && std::sqrt(rr) > target; ++iteration) {
    Vector q = schur(s);
    project(q);
    const double alpha = rr / s.dot(q);
    p += alpha * s;
    r -= alpha * q;
    const double next = r.squaredNorm();
    s = r + (next / rr) * s;
    rr = next;
  }
  out.iterations = iteration;
  out.residual = rhs.norm() > 0 ? std::sqrt(rr) / rhs.norm() : 0;
  if (std::sqrt(rr) > target)
    throw std::runtime_error("hydrodynamic tortuosity: no convergence in " + std::to_string(options.max_iterations) +
                             " iterations (relative residual " + std::to_string(out.residual) + ")");
  const Vector vel = inverse_a(f + d.transpose() * p);
  out.unknowns = n.nu + n.nv + n.np;
  // Cell-centred velocities of the image's pixels, the mean of their two faces on each axis.
  const auto face_value = [&](const std::vector<Index>& face, Index offset, int i, int j) {
    if (i < 0) return 0.0;
    const Index k = face[static_cast<std::size_t>(b.cell(i, b.wrap_y(j)))];
    return k >= 0 ? vel[offset + k] : 0.0;
  };
  double speed = 0, down = 0, p_above = 0, p_below = 0;
  for (int j = 0; j < image.ny; ++j)
    for (int i = 0; i < image.nx; ++i) {
      const int bj = j + buffer;
      const auto k = static_cast<std::size_t>(b.cell(i, bj));
      if (!b.fluid[k]) continue;
      const double ux = 0.5 * (face_value(n.u, 0, i, bj) + face_value(n.u, 0, b.right(i), bj));
      const double uy = 0.5 * (face_value(n.v, n.nu, i, bj) + face_value(n.v, n.nu, i, bj + 1));
      const auto at = static_cast<std::size_t>(i + image.nx * j);
      out.ux[at] = ux, out.uy[at] = uy, out.pressure[at] = p[n.p[k]];
      speed += std::hypot(ux, uy);
      down -= uy;
    }
  if (!(down > 0)) throw std::invalid_argument("image: no flow from the top to the bottom");
  out.tortuosity = speed / down;
  // Darcy over the medium: the superficial velocity q against the force and the pressure drop
  // across it (the mean pressure of the buffer rows next to it; zero without buffers, where the
  // box is periodic and the force alone drives).
  if (buffer > 0) {
    int above = 0, below = 0;
    for (int i = 0; i < b.nx; ++i) {
      if (const Index k = n.p[static_cast<std::size_t>(b.cell(i, b.ny - buffer))]; k >= 0) p_above += p[k], ++above;
      if (const Index k = n.p[static_cast<std::size_t>(b.cell(i, buffer - 1))]; k >= 0) p_below += p[k], ++below;
    }
    p_above /= std::max(1, above), p_below /= std::max(1, below);
  }
  const double q = down / static_cast<double>(pixels);            // per pixel of the medium, solid ones at 0
  const double drive = 1 + (p_above - p_below) / (image.ny + 1);  // force per volume, f = 1
  out.superficial_velocity = q;
  out.permeability = q / drive * image.pixel * image.pixel;  // k = mu q / (f + dp/dy), length^2
  return out;
}

bool FlowOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!(tolerance > 0) || !(tolerance < 1)) return fail("flow tolerance: must be in (0, 1)");
  if (max_iterations < 1) return fail("flow max-iterations: must be >= 1");
  if (buffer_rows < -1) return fail("flow buffer-rows: must be >= 0 (or -1: automatic)");
  return true;
}

}  // namespace softdrop
