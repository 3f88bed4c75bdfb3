#pragma once
// `softdrop optimize --islands K`: K searches side by side, each a run of the history, with
// migrations between them (on threads, or across MPI ranks).

#include <CLI/CLI.hpp>

#include "cli/host.hpp"
#include "cli/search_setup.hpp"

namespace softdrop::cli {

/// optimize with --islands K > 1, or resuming one of islands: the library's run (`run`), driven on
/// `drive` (the MPI ranks; nullptr: this process's threads), with the program's lines and summary.
int run_islands(const SearchOutput& out, const SearchRun& run, Host* host, const IslandsDrive* drive);

}  // namespace softdrop::cli
