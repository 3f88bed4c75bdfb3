#pragma once
/// \file open_mode.hpp
/// How a softdrop database file (search histories and sweep stores share one) is opened, and the
/// error when it cannot be.

#include <stdexcept>
#include <string>

namespace softdrop {

/// How to open a database file.
enum class OpenMode {
  read_only,  ///< must exist and be a softdrop database
  create      ///< created if missing; an existing file must be a softdrop database
};

/// A file that is not a usable softdrop database (missing, not SQLite, foreign, newer, truncated,
/// corrupted, unwritable): one line naming the file. The Python module raises it as StoreError.
struct DatabaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace softdrop
