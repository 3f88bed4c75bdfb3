#include "cli/kept_arrangement.hpp"

#include <cmath>

#include "cli/output.hpp"

namespace softdrop::cli {

std::string in_search_basis(const ArrangementValues& v, bool brief) {
  if (!v.robust()) return "one droplet from x0 = W/2";
  const std::string over = v.objective + " over " + std::to_string(v.starts) + " starts, ";
  const std::string mean = "the mean of " + std::to_string(v.re_runs) + " re-runs";
  if (brief) return over + (v.re_runs > 0 ? mean : std::string("as kept, no re-run"));
  return over + "a droplet that did not pass counted as T = 1; " +
         (v.re_runs > 0 ? mean + " on fresh starts" : std::string("the value it was kept with, not re-run"));
}

std::string held_out_text(const ValidationRecord& v) {
  const std::string starts = std::to_string(v.starts) + " random starts";
  if (!std::isfinite(v.mean_t)) return "no droplet of " + starts + " passed";
  return "<T> = " + (std::isfinite(v.standard_error) ? with_error(v.mean_t, v.standard_error) : fmt(v.mean_t, 4)) +
         " over " + starts + ", " + std::to_string(v.passed) + " passed";
}

}  // namespace softdrop::cli
