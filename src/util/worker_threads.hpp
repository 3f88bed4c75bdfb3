#pragma once
// How many worker threads an options struct's `threads` asks for: 0 means all cores.

#include <algorithm>
#include <string>
#include <thread>

#include "util/validation.hpp"

namespace softdrop::detail {

/// The most worker threads an options struct accepts.
constexpr int kMaxThreads = 4096;

/// Whether `threads` is a count an options struct accepts, 0 (all cores) to kMaxThreads; if not,
/// `why` names it.
inline bool valid_threads(int threads, std::string* why) {
  if (threads >= 0 && threads <= kMaxThreads) return true;
  return fail(why, "threads = " + std::to_string(threads) + ": must be in [0, " + std::to_string(kMaxThreads) +
                       "] (0: all cores)");
}

inline int worker_threads(int requested) {
  return requested > 0 ? requested : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
}

}  // namespace softdrop::detail
