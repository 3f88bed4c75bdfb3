#pragma once
// Reading a database's write-ahead log (its -wal file) before SQLite does (internal to the store).
// SQLite reads the frames of a WAL up to the first one whose checksum fails and silently drops the
// rest, and the next writer then overwrites them: a damaged byte early in the log loses every
// transaction committed after it, without a word. The store reads the log first and refuses it.

#include <cstdint>
#include <string>

namespace softdrop::detail {

/// What the frames of a -wal file hold, as SQLite's recovery would see them.
struct WalReport {
  bool present = false;               ///< a -wal file longer than its 32-byte header
  std::int64_t bytes = 0;             ///< the file's size
  bool header_valid = false;          ///< magic, version, page size and checksum hold
  std::int64_t frames = 0;            ///< whole frames in the file
  std::int64_t valid_frames = 0;      ///< frames SQLite's recovery keeps reading (up to the first bad one)
  std::int64_t first_bad_frame = -1;  ///< 1-based index of the first frame that fails, -1: none
  /// Commit frames of the header's generation (its salts) after the first bad frame: committed
  /// transactions that recovery would drop. Frames of an earlier generation (left after a
  /// checkpoint reset the log) have other salts and are not counted.
  std::int64_t lost_commits = 0;
};

/// Reads `wal_path` (no such file: a report with present = false). Never writes.
WalReport read_wal(const std::string& wal_path);

/// "" if SQLite would use every committed transaction of the log; otherwise one phrase saying what
/// is damaged and what recovery would drop. A log whose only bad frames are the uncommitted tail
/// of its last transaction (a write cut short) is not damage: SQLite drops nothing committed.
std::string wal_damage(const WalReport& r);

}  // namespace softdrop::detail
