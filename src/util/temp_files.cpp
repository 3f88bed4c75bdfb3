#include "temp_files.hpp"

#include <unistd.h>

#include <array>
#include <atomic>

namespace softdrop::detail {
namespace {
// A fixed table, so that a signal handler can read it without locks or allocation. A command
// writes a handful of files at once at most.
constexpr int kSlots = 64;
std::array<std::atomic<const char*>, kSlots> g_names{};
}  // namespace

TempName::TempName(const std::string& final_path) : name_(final_path + ".tmp." + std::to_string(::getpid())) {
  for (int i = 0; i < kSlots; ++i) {
    const char* expected = nullptr;
    if (g_names[static_cast<std::size_t>(i)].compare_exchange_strong(expected, name_.c_str())) {
      slot_ = i;
      break;
    }
  }
}

TempName::~TempName() {
  if (slot_ >= 0) g_names[static_cast<std::size_t>(slot_)].store(nullptr);
}

void remove_temp_files() noexcept {
  for (auto& name : g_names)
    if (const char* p = name.load()) ::unlink(p);
}

}  // namespace softdrop::detail
