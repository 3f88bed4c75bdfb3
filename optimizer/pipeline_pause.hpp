#pragma once
// A fault-injection point of the speculative search pipeline (internal, for tests): while it is
// above 0, completing a generation pauses that many milliseconds after taking the generation's
// candidates and before recording it complete, the window in which no worker may look at the
// pipeline's state (tests/search_test.cpp holds the pipeline to that).

#include <atomic>

namespace softdrop::detail {
extern std::atomic<int> pipeline_completion_pause_ms;
}  // namespace softdrop::detail
