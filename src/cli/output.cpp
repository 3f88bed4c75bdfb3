#include "cli/output.hpp"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace softdrop::cli {

void check_output_path(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw std::runtime_error(option + " '" + path + "': is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(option + " '" + path + "': directory '" + dir.string() +
                             "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(option + " '" + path + "': directory is not writable");
}

Progress::Progress(std::string label)
    : label_(std::move(label)), last_(std::chrono::steady_clock::now()), tty_(::isatty(2) != 0) {}

void Progress::update(long done, long total) {
  const auto now = std::chrono::steady_clock::now();
  if (done != total && now - last_ < std::chrono::seconds(1)) return;
  last_ = now;
  std::cerr << (tty_ ? "\r" : "") << label_ << ": " << done << "/" << total
            << (tty_ && done != total ? "" : "\n") << std::flush;
}

std::string fmt(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace softdrop::cli
