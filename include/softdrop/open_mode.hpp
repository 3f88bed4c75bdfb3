#pragma once
/// \file open_mode.hpp
/// How a softdrop database file (search histories and sweep stores share one) is opened.

namespace softdrop {

/// How to open a database file.
enum class OpenMode {
  read_only,  ///< must exist and be a softdrop database
  create      ///< created if missing; an existing file must be a softdrop database
};

}  // namespace softdrop
