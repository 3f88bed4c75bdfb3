#pragma once
// Image media (softdrop/medium.hpp): the checks of an image medium, and the image files' readers
// and writers. Private to softdrop_media.
#include <string>

#include "softdrop/medium.hpp"

namespace softdrop::detail {

/// The extension of a file's name in lower case, with its dot (".png"); empty if it has none.
std::string lower_extension(const std::string& path);

/// Medium::IsValid's test of an image medium: a valid image, no grains, and the image's box.
bool image_is_valid(const Medium& medium, std::string* why);

/// The binary image in a PNG, TIFF or .npy file (by its extension), rows turned so that row 0 is
/// the bottom, with pixel 1 and periodic true. Throws std::runtime_error naming the file.
PoreImage read_image_file(const std::string& path);

/// The file's bytes of an image (PNG, TIFF or .npy by the extension), first row at the top: white,
/// True, pore.
std::string image_file_bytes(const std::string& path, const PoreImage& image);

}  // namespace softdrop::detail
