#pragma once
// A program that runs softdrop's commands inside its own process (the Python module) rather than
// from a shell. The command reports each committed generation or medium to it, may be stopped
// there, hands it the JSON summary instead of printing, and leaves the signals to it.

#include <functional>
#include <nlohmann/json.hpp>

namespace softdrop::cli {

struct Host {
  /// Called on the calling thread after each generation (optimize) or medium (sweep) is
  /// committed, with what the progress line reports, as JSON (see the Python module's
  /// optimize and sweep for the keys). Returning false stops the command there, as the program's
  /// first Ctrl-C does: the run or sweep is marked interrupted and can be resumed.
  std::function<bool(const nlohmann::json& event)> on_progress;
  /// Set by the command: its summary, what `--format json` prints (nothing is printed on stdout).
  nlohmann::json summary;
};

}  // namespace softdrop::cli
