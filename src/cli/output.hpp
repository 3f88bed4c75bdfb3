#pragma once
// Output helpers shared by the CLI commands: checked output paths, progress on stderr.

#include <chrono>
#include <string>

namespace softdrop::cli {

/// Throws std::runtime_error naming `option` if `path` cannot be created (missing directory,
/// or a directory itself). Called before any long work so that a bad path fails fast.
void check_output_path(const std::string& option, const std::string& path);

/// Throttled progress line on stderr ("label: done/total"), at most about once per second, and
/// always for the last item.
class Progress {
 public:
  explicit Progress(std::string label);
  void update(long done, long total);

 private:
  std::string label_;
  std::chrono::steady_clock::time_point last_;
  bool tty_;
};

/// Formats a double with the given significant digits (17 = round trip).
std::string fmt(double v, int digits = 17);

}  // namespace softdrop::cli
