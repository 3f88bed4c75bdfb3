#pragma once
// What `simulate` writes about its runs, shared by one droplet a start (simulate_command.cpp) and
// two (simulate_two.cpp): a run's record, the --runs columns of a run, the rows of its path and
// snapshots, the medium's line and record, and the ending (the summary printed, a stop reported).
#include <functional>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "cli/output.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop::cli {

/// The --runs columns of a run, after its key columns (droplet; order for pairs).
inline constexpr const char* kRunColumns =
    "start_x,outcome,tortuosity,steps,touched,min_area_ratio,max_penetration,shaken_at,route_tortuosity";
/// A run's values of kRunColumns, comma-separated (empty where not defined: T unless passed).
void write_run_columns(std::ostream& o, const RunSummary& r);
/// A run's JSON record: kRunColumns and the reason.
nlohmann::json run_record(const RunSummary& r);
/// The rows of a run's path (time,x,y) and snapshots (time,mass,x,y), each after `key` (its key
/// columns and a comma).
void write_path_rows(std::ostream& o, const std::string& key, const RunSummary& r);
void write_snapshot_rows(std::ostream& o, const std::string& key, const RunSummary& r);

/// The medium's record and its line of the table.
nlohmann::json medium_record(const Medium& medium, double porosity);
std::string medium_line(const Medium& medium, double porosity);
/// "N grains" or "an image of C x R pixels of h", then the porosity (to `digits`), the box and its
/// sides: the medium in a line's words.
std::string medium_words(const Medium& medium, double porosity, int digits);

/// Writes a CSV file at once (none if path is empty): the header (its names checked against the
/// table of names) and the rows `rows` writes.
void write_csv(const std::string& path, const std::string& header, const std::function<void(std::ostream&)>& rows);

/// Prints the summary (JSON or the table, as `format` says) and, if a signal stopped the command,
/// says so on stderr: `ran` of `asked` `what` (droplets, pairs) in the outputs. Returns the exit code.
int finish_simulate(const std::string& format, const nlohmann::json& j, const std::string& table,
                    const StopOnSignal& stop, std::size_t ran, long asked, const char* what);

}  // namespace softdrop::cli
