#pragma once
// Running the softdrop program from tests: exit code, stdout and stderr of one invocation.

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#if defined(__SANITIZE_ADDRESS__)
#define SOFTDROP_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOFTDROP_TEST_ASAN 1
#endif
#endif

namespace softdrop::test {

/// Whether this test build runs under AddressSanitizer (slower; reserves terabytes of address space).
#ifdef SOFTDROP_TEST_ASAN
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif

struct Result {
  int code;  ///< exit code, -1 if killed by a signal
  std::string out, err;
};

/// A directory of this test process's own, made on first use and removed with everything in it when the
/// process exits normally, so a run of the suite leaves nothing in the temporary directory. A test that
/// crashes leaves its files for inspection. A forked child that exits normally does not remove its
/// parent's directory.
class TempDir {
 public:
  TempDir() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / ("softdrop_test_" + std::to_string(::getpid()) + "_XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a directory like " + pattern);
    path_ = pattern;
    // The same permissions as /tmp, for the tests that run the program as another user.
    std::filesystem::permissions(path_, std::filesystem::perms::all | std::filesystem::perms::sticky_bit);
  }
  ~TempDir() {
    std::error_code ignored;
    if (::getpid() == owner_) std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  pid_t owner_ = ::getpid();
};

/// This test process's temporary directory (see TempDir).
inline const std::filesystem::path& temp_dir() {
  static const TempDir dir;
  return dir.path();
}

/// A path in this test process's temporary directory.
inline std::string temp_path(const std::string& name) { return (temp_dir() / name).string(); }

/// temp_path(name) with no file there, nor SQLite's -wal and -shm companions.
inline std::string fresh_path(const std::string& name) {
  const std::string p = temp_path(name);
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(p + suffix);
  return p;
}

/// fresh_path's short name.
inline std::string fresh(const std::string& name) { return fresh_path(name); }

/// The first line of a text file ("" if there is none).
inline std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

/// Runs a shell command line, capturing its stdout, stderr and exit code.
inline Result run_shell(const std::string& command) {
  const std::string err_path = temp_path("stderr.txt");
  const std::string cmd = command + " 2>" + err_path;
  Result r{};
  FILE* pipe = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_path);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_path);
  return r;
}

/// Runs `softdrop ARGS` through the shell.
inline Result run(const std::string& args) { return run_shell(std::string(SOFTDROP_CLI) + " " + args); }

}  // namespace softdrop::test
