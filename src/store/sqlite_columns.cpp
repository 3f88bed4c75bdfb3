// A column's value read as the type a softdrop file stores there (sqlite_file.hpp): anything else,
// or text that is not UTF-8, is a damaged or edited file, refused with the column's name.
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "sqlite_file.hpp"

namespace softdrop::detail {

namespace {
[[noreturn]] void mistyped(const SQLite::Column& c, const char* expected) {
  const char* type = c.isNull()    ? "NULL"
                     : c.isText()  ? "text"
                     : c.isBlob()  ? "a blob"
                     : c.isFloat() ? "a real"
                                   : "an integer";
  throw std::runtime_error(std::string("column ") + c.getName() + " holds " + type + ", expected " + expected +
                           " (damaged or edited file?)");
}
}  // namespace

double as_real(const SQLite::Column& c) {
  if (!c.isFloat() && !c.isInteger()) mistyped(c, "a number");
  return c.getDouble();
}

std::int64_t as_int64(const SQLite::Column& c) {
  if (!c.isInteger()) mistyped(c, "an integer");
  return c.getInt64();
}

int as_int(const SQLite::Column& c) {
  const std::int64_t v = as_int64(c);
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    throw std::runtime_error(std::string("column ") + c.getName() + " holds " + std::to_string(v) +
                             ", out of range (damaged or edited file?)");
  return static_cast<int>(v);
}

namespace {
// Whether `s` is well-formed UTF-8 (no overlong forms, surrogates or code points past U+10FFFF).
bool utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    const int extra = b < 0x80 ? 0 : (b >> 5) == 0x6 ? 1 : (b >> 4) == 0xe ? 2 : (b >> 3) == 0x1e ? 3 : -1;
    if (extra < 0 || i + 1 + static_cast<std::size_t>(extra) > s.size()) return false;  // not a lead byte, or cut short
    std::uint32_t cp = extra == 0 ? b : b & (0x3fu >> extra);
    for (int k = 1; k <= extra; ++k) {
      const auto c = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      if ((c >> 6) != 0x2) return false;
      cp = (cp << 6) | (c & 0x3fu);
    }
    static constexpr std::uint32_t kLeast[] = {0, 0x80, 0x800, 0x10000};
    if (cp < kLeast[extra] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return false;
    i += 1 + static_cast<std::size_t>(extra);
  }
  return true;
}
}  // namespace

std::string as_text(const SQLite::Column& c) {
  if (!c.isText()) mistyped(c, "text");
  std::string s = c.getString();
  if (!utf8(s))
    throw std::runtime_error(std::string("column ") + c.getName() +
                             " holds text that is not UTF-8 (damaged or edited file?)");
  return s;
}

}  // namespace softdrop::detail
