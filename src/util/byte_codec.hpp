#pragma once
// Values as bytes, for messages between the processes of one job (same build, same kind of
// node): trivially copyable values as they lie in memory, strings and vectors with their length
// first. Reading past the end, or a length that cannot fit, throws std::invalid_argument.

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace softdrop::detail {

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    out += s;
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string out;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes, const char* what) : bytes_(bytes), what_(what) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  std::string get_string() {
    const auto n = count(1);
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  template <class T>
  std::vector<T> get_vector() {
    const auto n = count(sizeof(T));
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  bool at_end() const { return at_ == bytes_.size(); }
  [[noreturn]] void fail(const std::string& why) const { throw std::invalid_argument(std::string(what_) + ": " + why); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) fail("truncated");
  }
  // A length read, checked to fit in what is left, for items of `size` bytes.
  std::size_t count(std::size_t size) {
    const auto n = get<std::uint64_t>();
    if (n > (bytes_.size() - at_) / size) fail("truncated");
    return static_cast<std::size_t>(n);
  }
  const std::string& bytes_;
  const char* what_;
  std::size_t at_ = 0;
};

}  // namespace softdrop::detail
