// A robust objective's in-search value of a kept arrangement, read off the stored generations.
#include <stdexcept>
#include <string>

#include "softdrop/store.hpp"

namespace softdrop {

KeptValue kept_value(const std::vector<GenerationRecord>& generations, std::int64_t kept) {
  // Generations are numbered 0, 1, 2, ... (History::generations checks it), so g is at index g.
  if (kept < 0 || kept >= static_cast<std::int64_t>(generations.size()))
    throw std::invalid_argument("generation " + std::to_string(kept) + ": not stored");
  auto end = static_cast<std::size_t>(kept);
  while (end + 1 < generations.size() && generations[end + 1].accepted < 0) ++end;
  return {generations[end].best_t, static_cast<std::int64_t>(end) - kept};
}

}  // namespace softdrop
