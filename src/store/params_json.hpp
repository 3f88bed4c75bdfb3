#pragma once
/// \file params_json.hpp
/// A search's options as a flat JSON object whose keys are the command line's long option names
/// ("lambda", "nrt", "max-steps", ...): what the history stores with each run, and what a resume
/// compares the command line against.

#include <string>
#include <vector>

#include "softdrop/search.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {

/// Every option of `options`, numbers written so that they read back bit for bit.
std::string search_params_to_json(const SearchOptions& options);
/// Reads them back from a JSON object (extra keys are ignored). Throws std::runtime_error naming a
/// missing or mistyped key.
SearchOptions search_params_from_json(const std::string& json);
/// The keys search_params_to_json writes.
std::vector<std::string> search_param_keys();

/// The keys of the droplet and of its exit conditions that `softdrop simulate` also takes: what a
/// stored run hands to simulate to push the same droplet the same way.
std::vector<std::string> simulation_param_keys();

/// A sweep's options, the same way (keys: porosities, media, droplets, seed, the medium's and the
/// droplet's option names). Two sweeps are the same sweep exactly when these texts are equal.
std::string sweep_params_to_json(const SweepOptions& options);
/// Reads them back; throws std::runtime_error naming a missing or mistyped key.
SweepOptions sweep_params_from_json(const std::string& json);

}  // namespace softdrop
