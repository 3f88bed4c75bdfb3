#pragma once
// How many worker threads an options struct's `threads` asks for: 0 means all cores.

#include <algorithm>
#include <thread>

namespace softdrop::detail {

/// The most worker threads an options struct accepts.
constexpr int kMaxThreads = 4096;

inline int worker_threads(int requested) {
  return requested > 0 ? requested : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
}

}  // namespace softdrop::detail
