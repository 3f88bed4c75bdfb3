#pragma once
// A search's and a sweep's options as named values, the names being the program's long options
// ("lambda", "r-min", "migrate-every"): what the Python module builds a SearchRun or a SweepRun
// from, with the program's defaults and presets, so that each option has one name, one default and
// one check whichever way it is given.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "softdrop/service.hpp"

namespace softdrop {

/// The parameters stored with a new run: the search's (search_params_to_json) and how its first
/// arrangement is made (medium: the grain file or ""; grains, width, height, r-min, r-max,
/// radius-distribution, r-median, r-sigma, walls, medium-seed). set_search_run_values reads them.
nlohmann::json search_run_params(const SearchOptions& search, const SearchStart& start);
/// The stored and command-line spelling of SearchRun::own_island_starts: "own" or "shared".
const char* island_starts_name(bool own);
/// Sets the islands' keys of the stored parameters (islands, migrate-every, migration,
/// island-starts) to `run`'s.
void set_island_params(const SearchRun& run, nlohmann::json* params);

/// The named values of a run: its stored parameters (wanted_params) with the islands' keys always
/// present. Each value's JSON type is the type the name takes.
nlohmann::json search_run_values(const SearchRun& run);
/// Sets the search's options, the start's and the islands' of `run` from `values` (the names of
/// search_run_values; extra names are ignored). Throws std::invalid_argument naming a mistyped
/// value or an unknown strategy, objective, radius distribution or migration.
void set_search_run_values(const nlohmann::json& values, SearchRun* run);

/// The names of the generated starting medium's options (grains, width, ..., medium-seed): with a
/// grain file they would have no effect.
const std::vector<std::string>& search_medium_keys();

/// Applies the preset `name` ("paper": the paper's algorithm, strategy paper, lambda 1, no
/// relocation and the single objective) to the search options not among `given`; returns the names
/// it set. "" does nothing; another name throws std::invalid_argument naming --preset.
std::vector<std::string> apply_search_preset(const std::string& name, const std::vector<std::string>& given,
                                             SearchOptions* search);

/// False, with why naming it, when a name among `given` is an option of a strategy or objective
/// that `search` does not use ("sigma: an option of --strategy cmaes, not used by --strategy es").
bool given_options_used(const SearchOptions& search, const std::vector<std::string>& given, std::string* why);

/// The program's default sweep (`softdrop sweep` with no options): SweepOptions{} on overlapping
/// grains.
SweepOptions default_sweep();
/// The named values of a sweep: its stored parameters (sweep_params_to_json) with the second
/// droplet's keys always present ("second-droplet" "" when there is none).
nlohmann::json sweep_values(const SweepOptions& sweep);
/// The sweep of `values` (the names of sweep_values). Throws std::invalid_argument naming a
/// mistyped or unknown value, or second-after or second-offset-x among `given` without a second
/// droplet.
SweepOptions sweep_of_values(const nlohmann::json& values, const std::vector<std::string>& given);
/// Applies the preset `name` (quick: porosities 0.7, 0.8, 0.9 x 2 media x 8 droplets; paper: 10
/// porosities x 200 media x 200 droplets) to porosities, media and droplets unless among `given`.
/// "" does nothing; another name throws std::invalid_argument naming --preset.
void apply_sweep_preset(const std::string& name, const std::vector<std::string>& given, SweepOptions* sweep);

}  // namespace softdrop
