#pragma once
/// \file medium.hpp
/// Porous media: a W x H box with disc grains, periodic in x by default, and their generators.
///
/// Grain files: the documented JSON and CSV formats in which media are saved and loaded.
///
/// JSON (`.json`):
///   {"format": "softdrop-medium", "version": 1, "width": 500, "height": 500, "periodic": true,
///    "grains": [{"x": 10.5, "y": 20.0, "r": 12.0}, ...]}
/// CSV (any other extension): optional comment lines `# width=500`, `# height=500`,
/// `# periodic=true`, then a header line `x,y,r` and one grain per line. Missing width/height
/// comments are an error.
///
/// Void fraction of a medium's box: exact (analytic area of the union of discs) and Monte Carlo.

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace softdrop {

/// One rigid disc. Units: length units of the simulation (pixel-like, see README).
struct Grain {
  double x = 0;  ///< centre x
  double y = 0;  ///< centre y
  double r = 0;  ///< radius, > 0
  bool operator==(const Grain&) const = default;
};

/// The largest width or height of a box, in length units (the droplet's radius is about 10). Past
/// it a grain's position keeps too few digits for a contact, and past about 1e154 the box's area
/// is no longer a finite double, so its porosity would be NaN.
inline constexpr double kMaxBoxSide = 1e9;

/// A binary image of a pore space, pixel by pixel: pixel (i, j), column i from x = 0 and row j
/// from y = 0 at the bottom, is pore[i + nx j], 1 for pore and 0 for solid. Its box is nx pixel by
/// ny pixel. (Image files and numpy arrays list their rows from the top; the readers turn them.)
struct PoreImage {
  int nx = 0, ny = 0;    ///< columns and rows
  double pixel = 1;      ///< side of a pixel, length units
  bool periodic = true;  ///< periodic in x (otherwise solid side walls at x = 0 and x = W)
  std::vector<std::uint8_t> pore;
  /// Checks the size, the pixel (finite, > 0) and that every value is 0 or 1; names what is wrong.
  bool IsValid(std::string* why) const;
  double porosity() const;  ///< the share of pore pixels
  bool operator==(const PoreImage&) const = default;
};

/// A medium: the box [0, width) x [0, height] and its grains, or the pore space of an image.
struct Medium {
  double width = 500;    ///< W, length units
  double height = 500;   ///< H, length units
  bool periodic = true;  ///< periodic in x (otherwise solid side walls at x = 0 and x = W)
  std::vector<Grain> grains;
  /// An image medium's pore space (image_medium, load_image_medium): its solid is what the
  /// droplet meets, through a signed distance field, and its box is the image's. Null for a
  /// medium of grains; an image medium has no grains.
  std::shared_ptr<const PoreImage> image;

  /// Checks box size (positive, at most kMaxBoxSide), finiteness and positive radii, or the image
  /// and its box; names the first bad value in `why`.
  bool IsValid(std::string* why) const;
  /// Equal boxes, grains and images (compared pixel by pixel).
  bool operator==(const Medium& other) const;
};

/// How grains are placed.
enum class MediumKind {
  overlapping,      ///< Boolean model: uniform centres, discs may overlap
  non_overlapping,  ///< random sequential addition with a minimum surface gap
  /// Non-overlapping by relaxation: the grains are put down at random, then pushed apart until
  /// every gap holds the same rule. It reaches lower porosities with wider gaps than random
  /// sequential addition, which jams.
  relaxed
};

/// Parses "overlapping" / "non-overlapping"; throws std::invalid_argument naming the value.
MediumKind parse_medium_kind(const std::string& name);
/// Every medium kind's name offered (without the spelling "nonoverlapping", also taken).
std::vector<std::string> medium_kind_names();
const char* to_string(MediumKind kind);

/// How grain radii are drawn.
enum class RadiusDistribution {
  uniform,   ///< uniform in [r_min, r_max]
  lognormal  ///< log-normal with median r_median and log-standard-deviation r_sigma, redrawn until
             ///< it falls in [r_min, r_max]
};

/// Parses "uniform" / "lognormal"; throws std::invalid_argument naming the value.
RadiusDistribution parse_radius_distribution(const std::string& name);
/// Every radius distribution's name, in the enum's order.
std::vector<std::string> radius_distribution_names();
const char* to_string(RadiusDistribution radii);

/// Creation data of a random medium.
struct MediumOptions {
  MediumKind kind = MediumKind::overlapping;
  double porosity = 0.8;  ///< target void fraction of the box, in (0, 1)
  /// If > 0, place exactly this many grains and ignore the porosity target (the search's media).
  int grains = 0;
  double width = 500;                                      ///< W, length units
  double height = 500;                                     ///< H, length units
  bool periodic = true;                                    ///< periodic in x
  double r_min = 16;                                       ///< smallest grain radius (2 droplet radii)
  double r_max = 48;                                       ///< largest grain radius (6 droplet radii)
  RadiusDistribution radii = RadiusDistribution::uniform;  ///< how radii are drawn
  double r_median = 28;                                    ///< log-normal: median radius (about sqrt(r_min r_max))
  double r_sigma = 0.4;                                    ///< log-normal: standard deviation of ln r
  double gap = 0.13;       ///< non-overlapping: min surface gap as a fraction of the larger radius
  std::uint64_t seed = 1;  ///< random seed
  /// Non-overlapping: consecutive failed placements after which the target is declared unreachable.
  int max_failed_attempts = 200000;

  bool IsValid(std::string* why) const;
};

/// Generates a medium. With `grains` > 0: that many grains, overlapping or not. Otherwise: overlapping: adds discs
/// until the exact porosity first drops to or below the target. Non-overlapping: random sequential addition keeping
/// every surface gap >= gap * larger radius and grains inside the box in y, until the target is reached; throws
/// std::runtime_error if the target cannot be reached (jamming). Relaxed: grains drawn at random until the porosity is
/// nearest the target (one grain more or fewer than non-overlapping placement stops at), then
/// relaxed to the same rule; throws std::runtime_error if relaxation cannot make room for them.
/// Throws std::invalid_argument for invalid options.
Medium generate_medium(const MediumOptions& options);

/// Largest grain file load_medium reads (checked before reading): 256 MiB.
constexpr std::uintmax_t kMaxGrainFileBytes = std::uintmax_t{256} << 20;
/// Most grains a grain file may hold, the same limit as for generated media.
constexpr std::size_t kMaxFileGrains = 10'000'000;

enum class GrainFileFormat { json, csv };
/// JSON for a `.json` name, CSV otherwise.
GrainFileFormat grain_file_format(const std::string& path);

/// Loads a grain file; throws std::runtime_error naming the file (and line) on any problem,
/// including a file larger than kMaxGrainFileBytes or with more than kMaxFileGrains grains. An
/// image file (is_image_file) loads as load_image_medium(path, 1, true) does.
Medium load_medium(const std::string& path);
/// Reads grain-file text from a stream (what load_medium does after opening the file); `name`
/// is the file name used in error messages.
Medium read_medium(std::istream& in, GrainFileFormat format, const std::string& name);

/// Saves a medium atomically (temporary file then rename): JSON for `.json`, otherwise CSV; an
/// image medium as save_image_medium saves it.
/// Values are written with 17 significant digits so that a load gives the same doubles.
void save_medium(const std::string& path, const Medium& medium);

/// The medium of an image's pore space, its box nx pixel by ny pixel. Throws
/// std::invalid_argument naming what is wrong: an image that is not valid, or has no pore pixel.
Medium image_medium(PoreImage image);

/// Whether `path` names an image medium by its extension: .png, .tif, .tiff or .npy (any case).
bool is_image_file(const std::string& path);

/// Loads a binary image as a medium: PNG (libpng) or TIFF (libtiff) of two grey levels, black and
/// white or 0 and 1, or a 2D numpy .npy array of booleans or of integers or floats 0 and 1. White,
/// 1 or True is pore (PoreSpy's convention); the file's first row is the top of the box. Each
/// pixel is `pixel` length units. Throws std::runtime_error naming the file for one that cannot be
/// read or is not binary, and std::invalid_argument for a bad pixel size or an image without pore.
Medium load_image_medium(const std::string& path, double pixel, bool periodic);

/// Saves an image medium's pore space as load_image_medium reads it back: PNG (white pore) or .npy
/// (booleans), by the extension, atomically. Throws std::invalid_argument for a medium of grains
/// or another extension.
void save_image_medium(const std::string& path, const Medium& medium);

/// Writes `content` to `path` atomically: a reader sees the old file or the whole new one.
void write_file_atomically(const std::string& path, const std::string& content);

/// Exact porosity: 1 - area(union of grains, clipped to the box) / (W H), periodic in x when the
/// medium is. Computed with Green's theorem over the uncovered circle arcs and covered box edges.
/// An image medium's is its share of pore pixels.
double exact_porosity(const Medium& medium);

/// Area of the union of the grains clipped to the box (length units squared).
double solid_area(const Medium& medium);

/// Monte Carlo estimate of the porosity from `samples` uniform points and its standard error.
struct PorosityEstimate {
  double porosity = 0;
  double standard_error = 0;
};
PorosityEstimate monte_carlo_porosity(const Medium& medium, std::int64_t samples, std::uint64_t seed);

}  // namespace softdrop
