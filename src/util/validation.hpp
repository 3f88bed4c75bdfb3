#pragma once
// Helpers of the IsValid functions: a message naming the parameter, and numbers printed exactly.

#include <charconv>
#include <string>

namespace softdrop::detail {

/// Stores `message` in `why` (if given) and returns false, for `return fail(why, "...")`.
inline bool fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

/// The shortest decimal that reads back as the same double (0.8, not 0.80000000000000004), for
/// messages and files alike.
inline std::string num(double v) {
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

}  // namespace softdrop::detail
