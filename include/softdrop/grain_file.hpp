#pragma once
/// \file grain_file.hpp
/// Grain files: the documented JSON and CSV formats in which media are saved and loaded.
///
/// JSON (`.json`):
///   {"format": "softdrop-medium", "version": 1, "width": 500, "height": 500, "periodic": true,
///    "grains": [{"x": 10.5, "y": 20.0, "r": 12.0}, ...]}
/// CSV (any other extension): optional comment lines `# width=500`, `# height=500`,
/// `# periodic=true`, then a header line `x,y,r` and one grain per line. Missing width/height
/// comments are an error.

#include <cstdint>
#include <iosfwd>
#include <string>

#include "softdrop/medium.hpp"

namespace softdrop {

/// Largest grain file load_medium reads (checked before reading): 256 MiB.
constexpr std::uintmax_t kMaxGrainFileBytes = std::uintmax_t{256} << 20;
/// Most grains a grain file may hold, the same limit as for generated media.
constexpr std::size_t kMaxFileGrains = 10'000'000;

enum class GrainFileFormat { json, csv };
/// JSON for a `.json` name, CSV otherwise.
GrainFileFormat grain_file_format(const std::string& path);

/// Loads a grain file; throws std::runtime_error naming the file (and line) on any problem,
/// including a file larger than kMaxGrainFileBytes or with more than kMaxFileGrains grains.
Medium load_medium(const std::string& path);
/// Reads grain-file text from a stream (what load_medium does after opening the file); `name`
/// is the file name used in error messages.
Medium read_medium(std::istream& in, GrainFileFormat format, const std::string& name);

/// Saves a medium atomically (temporary file then rename): JSON for `.json`, otherwise CSV.
/// Values are written with 17 significant digits so that a load gives the same doubles.
void save_medium(const std::string& path, const Medium& medium);

/// Writes `content` to `path` atomically: a reader sees the old file or the whole new one.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace softdrop
