// Binary images of pore spaces in files: PNG through libpng, TIFF through libtiff, and numpy's
// .npy format (a text header and the raw array), read and written.
#include <png.h>
#include <tiffio.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "media/image_medium.hpp"

namespace softdrop::detail {
namespace {

[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw std::runtime_error("image '" + path + "': " + what);
}

// Grey levels, first row at the top, as pore values: two levels at most, the higher pore (white,
// 1); one level alone is pore unless it is 0.
PoreImage from_levels(const std::string& path, int nx, int ny, const std::vector<double>& level) {
  if (nx < 1 || ny < 1) bad(path, "an empty image");
  std::set<double> levels;
  for (double v : level) {
    levels.insert(v);
    if (levels.size() > 2) bad(path, "not a binary image (more than two grey levels)");
  }
  const double pore = *levels.rbegin();
  if (levels.size() == 1 && pore == 0) bad(path, "no pore pixel (white, 1 or True is pore)");
  PoreImage im;
  im.nx = nx;
  im.ny = ny;
  im.pore.resize(level.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t from = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (ny - 1 - j);
      im.pore[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j] = level[from] == pore ? 1 : 0;
    }
  return im;
}

constexpr std::int64_t kMaxImagePixels = 64'000'000;

PoreImage read_png(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    bad(path, std::string("not a PNG image: ") + image.message);
  if (static_cast<std::int64_t>(image.width) * image.height > kMaxImagePixels) {
    png_image_free(&image);
    bad(path, "more than 6.4e7 pixels");
  }
  image.format = PNG_FORMAT_GRAY;
  std::vector<png_byte> grey(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, grey.data(), 0, nullptr))
    bad(path, std::string("unreadable PNG: ") + image.message);
  return from_levels(path, static_cast<int>(image.width), static_cast<int>(image.height),
                     std::vector<double>(grey.begin(), grey.end()));
}

PoreImage read_tiff(const std::string& path) {
  TIFFSetWarningHandler(nullptr);
  TIFFSetErrorHandler(nullptr);
  std::unique_ptr<TIFF, void (*)(TIFF*)> tif(TIFFOpen(path.c_str(), "r"), [](TIFF* t) {
    if (t) TIFFClose(t);
  });
  if (!tif) bad(path, "not a TIFF image, or unreadable");
  std::uint32_t w = 0, h = 0;
  TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &w);
  TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &h);
  if (static_cast<std::int64_t>(w) * h > kMaxImagePixels) bad(path, "more than 6.4e7 pixels");
  std::vector<std::uint32_t> rgba(static_cast<std::size_t>(w) * h);
  if (w == 0 || h == 0) bad(path, "an empty image");
  if (!TIFFReadRGBAImageOriented(tif.get(), w, h, rgba.data(), ORIENTATION_TOPLEFT, 0))
    bad(path, "a TIFF image libtiff cannot read as pixels");
  std::vector<double> level(rgba.size());
  for (std::size_t k = 0; k < rgba.size(); ++k) {
    const std::uint32_t p = rgba[k];
    if (TIFFGetR(p) != TIFFGetG(p) || TIFFGetG(p) != TIFFGetB(p)) bad(path, "not a binary image (a coloured pixel)");
    level[k] = TIFFGetR(p);
  }
  return from_levels(path, static_cast<int>(w), static_cast<int>(h), level);
}

// numpy's format: "\x93NUMPY", version, header length, a Python dict literal (descr,
// fortran_order, shape), then the array's bytes.
PoreImage read_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, "cannot open");
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, "\x93NUMPY", 6) != 0) bad(path, "not a numpy .npy file");
  std::uint32_t header_length = 0;
  unsigned char len[4] = {};
  if (magic[6] == 1) {
    in.read(reinterpret_cast<char*>(len), 2);
    header_length = len[0] | (len[1] << 8u);
  } else {
    in.read(reinterpret_cast<char*>(len), 4);
    header_length = len[0] | (len[1] << 8u) | (len[2] << 16u) | (static_cast<std::uint32_t>(len[3]) << 24u);
  }
  if (!in || header_length > 65536) bad(path, "a damaged .npy header");
  std::string header(header_length, '\0');
  if (!in.read(header.data(), header_length)) bad(path, "a damaged .npy header");
  std::smatch descr, order, shape;
  if (!std::regex_search(header, descr, std::regex(R"('descr'\s*:\s*'([<>|=])([a-z])(\d+)')")) ||
      !std::regex_search(header, order, std::regex(R"('fortran_order'\s*:\s*(True|False))")) ||
      !std::regex_search(header, shape, std::regex(R"('shape'\s*:\s*\(\s*(\d+)\s*,\s*(\d+)\s*,?\s*\))")))
    bad(path, "not a 2D numpy array (header " + header.substr(0, header.find('}') + 1) + ")");
  const char kind = descr[2].str()[0];
  const int size = std::stoi(descr[3].str());
  if (descr[1].str() == ">" && size > 1) bad(path, "a big-endian array; save it little-endian");
  const bool known = (kind == 'b' && size == 1) ||
                     ((kind == 'u' || kind == 'i') && (size == 1 || size == 2 || size == 4 || size == 8)) ||
                     (kind == 'f' && (size == 4 || size == 8));
  if (!known) bad(path, "an array of " + descr[0].str().substr(10) + "; booleans, integers or floats are read");
  const long long rows = std::stoll(shape[1].str()), cols = std::stoll(shape[2].str());
  if (rows < 1 || cols < 1) bad(path, "an empty image");
  if (rows * cols > kMaxImagePixels) bad(path, "more than 6.4e7 pixels");
  const std::size_t count = static_cast<std::size_t>(rows * cols);
  std::vector<char> bytes(count * static_cast<std::size_t>(size));
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) bad(path, "shorter than its array");
  std::vector<double> level(count);
  const bool fortran = order[1].str() == "True";
  for (std::size_t k = 0; k < count; ++k) {
    const char* b = bytes.data() + k * static_cast<std::size_t>(size);
    double v = 0;
    if (kind == 'f') {
      if (size == 4) {
        float f = 0;
        std::memcpy(&f, b, 4);
        v = f;
      } else {
        std::memcpy(&v, b, 8);
      }
    } else if (kind == 'i') {
      std::int64_t x = 0;
      std::memcpy(&x, b, static_cast<std::size_t>(size));
      if (size < 8 && (b[size - 1] & 0x80)) x -= std::int64_t{1} << (8 * size);  // sign
      v = static_cast<double>(x);
    } else {
      std::uint64_t x = 0;
      std::memcpy(&x, b, static_cast<std::size_t>(size));
      v = static_cast<double>(x);
    }
    if (v != 0 && v != 1) bad(path, "not a binary image (a value other than 0 and 1)");
    // C order: row by row; Fortran order: column by column.
    const std::size_t r = fortran ? k % static_cast<std::size_t>(rows) : k / static_cast<std::size_t>(cols);
    const std::size_t c = fortran ? k / static_cast<std::size_t>(rows) : k % static_cast<std::size_t>(cols);
    level[c + static_cast<std::size_t>(cols) * r] = v;
  }
  return from_levels(path, static_cast<int>(cols), static_cast<int>(rows), level);
}

// The image's values, first row at the top, as bytes: pore -> `pore`, solid -> 0.
std::vector<unsigned char> top_first(const PoreImage& im, unsigned char pore) {
  std::vector<unsigned char> out(im.pore.size());
  for (int j = 0; j < im.ny; ++j)
    for (int i = 0; i < im.nx; ++i)
      out[static_cast<std::size_t>(i) + static_cast<std::size_t>(im.nx) * (im.ny - 1 - j)] =
          im.pore[static_cast<std::size_t>(i) + static_cast<std::size_t>(im.nx) * j] ? pore : 0;
  return out;
}

}  // namespace

PoreImage read_image_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) bad(path, "no such file");
  const std::string extension = lower_extension(path);
  if (extension == ".png") return read_png(path);
  if (extension == ".npy") return read_npy(path);
  return read_tiff(path);
}

std::string image_file_bytes(const std::string& path, const PoreImage& im) {
  const std::string extension = lower_extension(path);
  if (extension == ".npy") {
    std::string header = "{'descr': '|b1', 'fortran_order': False, 'shape': (" + std::to_string(im.ny) + ", " +
                         std::to_string(im.nx) + "), }";
    // Padded with spaces and a newline so that the data start on a multiple of 64 bytes.
    const std::size_t total = 10 + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header += '\n';
    std::string out("\x93NUMPY\x01\x00", 8);
    out += static_cast<char>(header.size() & 0xff);
    out += static_cast<char>(header.size() >> 8);
    out += header;
    const std::vector<unsigned char> v = top_first(im, 1);
    out.append(v.begin(), v.end());
    return out;
  }
  if (extension != ".png") throw std::invalid_argument(path + ": an image medium is saved as .png or .npy");
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(im.nx);
  image.height = static_cast<png_uint_32>(im.ny);
  image.format = PNG_FORMAT_GRAY;
  const std::vector<unsigned char> grey = top_first(im, 255);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, grey.data(), 0, nullptr))
    throw std::runtime_error(path + ": " + image.message);
  std::string out(size, '\0');
  if (!png_image_write_to_memory(&image, out.data(), &size, 0, grey.data(), 0, nullptr))
    throw std::runtime_error(path + ": " + image.message);
  out.resize(size);
  return out;
}

}  // namespace softdrop::detail
