#pragma once
// Temporary files that a signal must not leave behind. Every output is written to `PATH.tmp.PID`
// and renamed over PATH when complete; if the program is ended by SIGINT, SIGTERM or SIGHUP in
// between, the command line's handlers call remove_temp_files(), so no half-written file remains.

#include <string>

namespace softdrop::detail {

/// The name `final_path + ".tmp." + PID`, registered while this object lives. The owner renames
/// or removes the file itself; destruction only unregisters the name.
class TempName {
 public:
  explicit TempName(const std::string& final_path);
  ~TempName();
  TempName(const TempName&) = delete;
  TempName& operator=(const TempName&) = delete;
  const std::string& str() const { return name_; }
  const char* c_str() const { return name_.c_str(); }

 private:
  std::string name_;
  int slot_ = -1;  // -1: more temporary files at once than the registry holds (not removed on a signal)
};

/// Unlinks every registered temporary file. Async-signal-safe: for signal handlers.
void remove_temp_files() noexcept;

}  // namespace softdrop::detail
