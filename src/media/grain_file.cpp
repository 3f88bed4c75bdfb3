#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "softdrop/medium.hpp"
#include "util/temp_files.hpp"
#include "util/validation.hpp"

namespace softdrop {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw std::runtime_error("grain file '" + path + "': " + what);
}

// Text from the file as it may be quoted in a message: bytes that are not printable ASCII as
// \xNN, and at most 40 characters.
std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out += c;
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  return "'" + out + (text.size() > 40 ? "...'" : "'");
}

double parse_number(const std::string& path, int line, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::size_t end = used;
  while (end < text.size() && std::isspace(static_cast<unsigned char>(text[end]))) ++end;
  if (used == 0 || end != text.size())
    bad(path, "line " + std::to_string(line) + ": " + printable(text) + " is not a number");
  return v;
}

bool parse_bool(const std::string& path, int line, std::string v) {
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  bad(path, "line " + std::to_string(line) + ": periodic must be true or false, got " + printable(v));
}

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string plain(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const auto at = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && at != std::string::npos ? what.substr(at + 2) : what;
}

// A number field of a JSON object, or a line naming the field and what it holds instead.
double number_at(const nlohmann::json& object, const char* key, const std::string& path, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) bad(path, where + "\"" + key + "\" is missing");
  if (!it->is_number()) bad(path, where + "\"" + key + "\" must be a number, not " + it->type_name());
  return it->get<double>();
}

Medium load_json(const std::string& path, std::istream& in) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    bad(path, "not valid JSON (" + plain(e) + ")");
  }
  if (!j.is_object()) bad(path, "top level must be an object");
  Medium m;
  if (!j.contains("format") || j["format"] != "softdrop-medium") bad(path, "\"format\" must be \"softdrop-medium\"");
  if (!j.contains("version") || j["version"] != 1) bad(path, "unsupported \"version\" (this program reads 1)");
  m.width = number_at(j, "width", path, "");
  m.height = number_at(j, "height", path, "");
  if (j.contains("periodic")) {
    if (!j["periodic"].is_boolean())
      bad(path, "\"periodic\" must be true or false, not " + std::string(j["periodic"].type_name()));
    m.periodic = j["periodic"].get<bool>();
  }
  if (!j.contains("grains")) bad(path, "\"grains\" is missing");
  const auto& grains = j["grains"];
  if (!grains.is_array()) bad(path, "\"grains\" must be an array");
  if (grains.size() > kMaxFileGrains)
    bad(path, std::to_string(grains.size()) + " grains, more than the limit of " + std::to_string(kMaxFileGrains));
  m.grains.reserve(grains.size());
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const auto& g = grains[i];
    const std::string where = "grain " + std::to_string(i) + ": ";
    if (!g.is_object()) bad(path, where + "must be an object with \"x\", \"y\" and \"r\", not " + g.type_name());
    m.grains.push_back(
        {number_at(g, "x", path, where), number_at(g, "y", path, where), number_at(g, "r", path, where)});
  }
  return m;
}

Medium load_csv(const std::string& path, std::istream& in) {
  Medium m;
  bool have_w = false, have_h = false, have_header = false, box_columns = false;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte order mark
    line = trim(line);
    if (line.empty()) continue;
    if (line[0] == '#') {
      const auto eq = line.find('=');
      if (eq == std::string::npos) continue;
      const std::string key = trim(line.substr(1, eq - 1)), value = trim(line.substr(eq + 1));
      if (key == "width")
        m.width = parse_number(path, number, value), have_w = true;
      else if (key == "height")
        m.height = parse_number(path, number, value), have_h = true;
      else if (key == "periodic")
        m.periodic = parse_bool(path, number, value);
      continue;
    }
    if (!have_header) {
      if (line == "x,y,r,width,height,periodic")
        box_columns = true;
      else if (line != "x,y,r")
        bad(path, "line " + std::to_string(number) + ": expected header x,y,r,width,height,periodic (or x,y,r), got " +
                      printable(line));
      have_header = true;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string field; f.size() <= 6 && std::getline(fields, field, ',');) f.push_back(trim(field));
    const std::size_t expected = box_columns ? 6 : 3;
    if (f.size() != expected)
      bad(path, "line " + std::to_string(number) + ": expected " + std::to_string(expected) + " fields " +
                    (box_columns ? "x,y,r,width,height,periodic" : "x,y,r"));
    if (m.grains.size() == kMaxFileGrains)
      bad(path,
          "line " + std::to_string(number) + ": more than the limit of " + std::to_string(kMaxFileGrains) + " grains");
    m.grains.push_back(
        {parse_number(path, number, f[0]), parse_number(path, number, f[1]), parse_number(path, number, f[2])});
    if (box_columns) {  // the box on every row, the same on every row
      const double w = parse_number(path, number, f[3]), h = parse_number(path, number, f[4]);
      const bool periodic = parse_bool(path, number, f[5]);
      if (have_w && !(w == m.width && h == m.height && periodic == m.periodic))
        bad(path, "line " + std::to_string(number) + ": width, height or periodic differ from the rows above");
      m.width = w, m.height = h, m.periodic = periodic, have_w = have_h = true;
    }
  }
  if (!have_header) bad(path, "no x,y,r,width,height,periodic header");
  if (!have_w || !have_h)
    bad(path, "missing the box: no grain row with width and height, and no '# width=' or '# height=' line");
  return m;
}

// A file that is plainly not text, by its first bytes, said for what it is: the grain parsers
// would name its binary header instead. Leaves the stream at its start.
void refuse_binary(const std::string& path, std::istream& in) {
  std::string head(16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  in.clear();
  in.seekg(0);
  const auto starts = [&](const std::string& magic) { return head.rfind(magic, 0) == 0; };
  if (starts(std::string("SQLite format 3\0", 16)))
    bad(path,
        "is an SQLite database (a history or sweep store?), not a list of grains; `softdrop export --db FILE --run N "
        "-o best.json` writes a search's arrangement as a grain file");
  if (starts("\x89PNG") || starts(std::string("II*\0", 4)) || starts(std::string("MM\0*", 4)) || starts("\x93NUMPY"))
    bad(path,
        "is an image or a numpy array, not a list of grains; name it .png, .tif or .npy to read it as an image "
        "medium");
}

}  // namespace

GrainFileFormat grain_file_format(const std::string& path) {
  return ends_with(path, ".json") ? GrainFileFormat::json : GrainFileFormat::csv;
}

Medium read_medium(std::istream& in, GrainFileFormat format, const std::string& name) {
  Medium m = format == GrainFileFormat::json ? load_json(name, in) : load_csv(name, in);
  std::string why;
  if (!m.IsValid(&why)) bad(name, why);
  return m;
}

Medium load_medium(const std::string& path) {
  if (is_image_file(path)) return load_image_medium(path, 1, true);
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec) bad(path, "cannot open (" + ec.message() + ")");
  if (std::filesystem::is_directory(status)) bad(path, "is a directory");
  // Checked before reading, so an absurd file is refused without filling memory.
  if (std::filesystem::is_regular_file(status)) {
    const auto bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > kMaxGrainFileBytes)
      bad(path, std::to_string(bytes >> 20) + " MiB, more than the limit of " +
                    std::to_string(kMaxGrainFileBytes >> 20) + " MiB for a grain file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, std::string("cannot open (") + std::strerror(errno) + ")");
  refuse_binary(path, in);
  return read_medium(in, grain_file_format(path), path);
}

void write_file_atomically(const std::string& path, const std::string& content) {
  const detail::TempName tmp_name(path);
  const std::string& tmp = tmp_name.str();
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
    out << content;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write '" + path + "': write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + ec.message());
  }
}

void save_medium(const std::string& path, const Medium& medium) {
  if (medium.image) {
    save_image_medium(path, medium);
    return;
  }
  std::ostringstream out;
  if (ends_with(path, ".json")) {
    nlohmann::json j;
    j["format"] = "softdrop-medium";
    j["version"] = 1;
    j["width"] = medium.width;
    j["height"] = medium.height;
    j["periodic"] = medium.periodic;
    j["grains"] = nlohmann::json::array();
    for (const Grain& g : medium.grains) j["grains"].push_back({{"x", g.x}, {"y", g.y}, {"r", g.r}});
    out << j.dump(1) << '\n';
  } else {
    // One plain table (pandas reads it as is): the box on every row. A medium without grains has
    // no row to carry it, and keeps it in comment lines (the older form, still read).
    const std::string periodic = medium.periodic ? "true" : "false";
    if (medium.grains.empty())
      out << "# softdrop medium\n# width=" << detail::num(medium.width) << "\n# height=" << detail::num(medium.height)
          << "\n# periodic=" << periodic << "\nx,y,r\n";
    else
      out << "x,y,r,width,height,periodic\n";
    for (const Grain& g : medium.grains)
      out << detail::num(g.x) << ',' << detail::num(g.y) << ',' << detail::num(g.r) << ',' << detail::num(medium.width)
          << ',' << detail::num(medium.height) << ',' << periodic << '\n';
  }
  write_file_atomically(path, out.str());
}

}  // namespace softdrop
