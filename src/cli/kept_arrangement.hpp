#pragma once
// How the commands that quote a search's kept arrangement (validate --db, export, render search)
// word its values, so that each says what `history --best` says.

#include <string>

#include "softdrop/store.hpp"

namespace softdrop::cli {

/// What the in-search value is a value of, e.g. "mean over 16 starts, a droplet that did not pass
/// counted as T = 1; the mean of 8 re-runs on fresh starts", or "one droplet from x0 = W/2"; brief:
/// in the few words a caption has room for ("mean over 16 starts, the mean of 8 re-runs").
std::string in_search_basis(const ArrangementValues& v, bool brief = false);

/// "<T> = 1.499 ± 0.012 over 200 random starts, 200 passed" (no error where one passed; "no
/// droplet of 200 random starts passed").
std::string held_out_text(const ValidationRecord& v);

}  // namespace softdrop::cli
