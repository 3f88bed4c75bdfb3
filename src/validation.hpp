#pragma once
// Helpers of the IsValid functions: a message naming the parameter, and numbers printed exactly.

#include <sstream>
#include <string>

namespace softdrop::detail {

/// Stores `message` in `why` (if given) and returns false, for `return fail(why, "...")`.
inline bool fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

/// A double with 17 significant digits (round trip), for error messages.
inline std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

}  // namespace softdrop::detail
