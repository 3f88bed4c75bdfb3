#pragma once
/// \file pore_tortuosity.hpp
/// Tortuosities of a medium's pore space on a pixel grid, beside the droplet's: the geometric
/// tortuosity (shortest paths through the pores), the diffusive one (a steady diffusion solve,
/// PoreSpy's tortuosity_fd definition) and the hydrodynamic one with the permeability (a creeping
/// flow solve). The medium is drawn as a binary image, pixel centres
/// inside no grain being pore, as PoreSpy's and TauFactor's images are.

#include <cstdint>
#include <string>
#include <vector>

#include "softdrop/medium.hpp"

namespace softdrop {

/// The medium drawn with `nx` pixels across its width (and as many rows as fill its height, at
/// least 1): a pixel is pore where its centre lies inside no grain (in an image medium, where it
/// lies in a pore pixel of the image). Throws std::invalid_argument
/// for nx < 2 or an image of more than kMaxPoreImagePixels pixels.
PoreImage pore_image(const Medium& medium, int nx);
inline constexpr std::int64_t kMaxPoreImagePixels = 64'000'000;

/// The geometric tortuosity: over the pore pixels of the top row (the starts), the length of the
/// shortest path through pore space to the bottom edge, over the box's height; first-order fast
/// marching on the pixel centres (Sethian), which converges to the continuous distance as the
/// pixels shrink. Starts that reach no bottom pore pixel are left out and counted.
struct GeometricTortuosity {
  double tortuosity = 0;             ///< mean over the connected starts of path length / H
  double standard_error = 0;         ///< of that mean over the starts (they are correlated: neighbours share paths)
  int starts = 0;                    ///< pore pixels of the top row
  int connected = 0;                 ///< of them, those with a path to the bottom
  double shortest = 0, longest = 0;  ///< the least and largest path length / H
  /// Every pixel's path length to the bottom edge (length units), as the image's pixels; infinite
  /// in the solid and in pores with no path down.
  std::vector<double> distance;
};
/// Throws std::invalid_argument naming the problem when no start is connected to the bottom.
GeometricTortuosity geometric_tortuosity(const PoreImage& image);

/// A path through the pore space: points in length units, from the top edge down to the bottom
/// edge, x running on across a periodic side.
struct PorePath {
  std::vector<double> x, y;
};
/// Up to `count` shortest paths, from starts spread evenly over the top pixels that reach the
/// bottom, each traced down `g`'s distance field (to whichever of the eight neighbours it falls
/// to most steeply) from the start's pixel to the bottom edge.
std::vector<PorePath> shortest_paths(const PoreImage& image, const GeometricTortuosity& g, int count);

/// The diffusive tortuosity: a steady diffusion through the pore space, concentration 1 above the
/// top row and 0 below the bottom row, no flux into the solid (or the walls), periodic in x if the
/// image is; finite volumes on the pixels, solved by sparse Cholesky (Eigen). Pore pixels joined
/// to neither edge carry no flux and are left out. tau = phi D / D_eff, with phi the image's
/// porosity and D_eff the flux through the box times H over W (PoreSpy's tortuosity_fd).
struct DiffusiveTortuosity {
  double tau = 0;                    ///< phi D / D_eff
  double formation_factor = 0;       ///< D / D_eff
  double effective_diffusivity = 0;  ///< D_eff / D
  double porosity = 0;               ///< of the image (all pore pixels)
  std::int64_t unknowns = 0;         ///< pore pixels solved for
  /// The concentration at every pixel, as the image's pixels (1 at the top, 0 at the bottom); NaN
  /// in the solid and in closed pockets.
  std::vector<double> concentration;
};
/// Throws std::invalid_argument naming the problem when no pore path joins the top and bottom.
DiffusiveTortuosity diffusive_tortuosity(const PoreImage& image);

/// How the creeping flow is solved (hydrodynamic_tortuosity).
struct FlowOptions {
  /// Rows of open fluid added above and below the image, the box then periodic in y, so that the
  /// flow leaving the bottom enters the top spread over the width, as from a reservoir; -1: the
  /// larger of 4 and 4 % of the image's rows. 0: the image itself is periodic in y (a unit cell).
  int buffer_rows = -1;
  double tolerance = 1e-8;     ///< relative residual of the pressure solve
  int max_iterations = 20000;  ///< conjugate-gradient iterations before giving up
  bool IsValid(std::string* why) const;
};

/// The hydrodynamic tortuosity and the permeability: creeping (Stokes) flow through the pore
/// space driven along -y by a uniform force on the fluid inside the image, no slip on the solid
/// pixels' faces (and on the walls, if the image has them), periodic in x if the image is; a
/// staggered grid (the velocities on the pixels' faces), solved exactly up to `tolerance`. As
/// Matyka 2008 and Duda, Koza and Matyka 2011 define it, T = <|u|> / <-u_y> over the image's
/// pore pixels (u at their centres). Both converge as the pixels shrink (the solid's edge is a
/// staircase of pixel faces): compare a resolution with its double.
struct HydrodynamicTortuosity {
  double tortuosity = 0;    ///< <|u|> / <-u_y> over the pore pixels
  double permeability = 0;  ///< Darcy's k = mu q / (f + dp/dy), length units squared; inf: nothing holds the flow
  double superficial_velocity = 0;  ///< q, the mean of -u_y over the image (solid at 0), in units of f h^2 / mu
  double porosity = 0;              ///< of the image (all pore pixels)
  int buffer_rows = 0;              ///< the buffer used
  int iterations = 0;               ///< of the pressure solve
  double residual = 0;              ///< its relative residual at the end
  std::int64_t unknowns = 0;        ///< velocities and pressures solved for
  /// Velocity (units of f h^2 / mu, h the pixel) and pressure (units of f h) at every pixel's
  /// centre, as the image's pixels; NaN in the solid and in closed pockets.
  std::vector<double> ux, uy, pressure;
};
/// Throws std::invalid_argument naming the problem when no pore path joins the top and bottom, or
/// for bad options; std::runtime_error if the solve does not converge.
HydrodynamicTortuosity hydrodynamic_tortuosity(const PoreImage& image, const FlowOptions& options = {});

}  // namespace softdrop
