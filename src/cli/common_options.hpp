#pragma once
// Option groups shared by the commands that build media and push droplets (simulate, optimize),
// so each option has one name, one help text and one default everywhere.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop::cli {

/// A medium to generate, or a grain file to load instead.
struct MediumArgs {
  MediumOptions options;
  std::string kind = "overlapping";
  std::string radii = "uniform";
  bool walls = false;
  std::string file;       ///< load instead of generating
  double pixel_size = 1;  ///< an image file's pixel side (length units)
};

/// The medium of --medium FILE: a grain file, or an image (is_image_file) of pixels --pixel-size
/// wide, periodic in x unless --walls.
Medium load_medium_file(const MediumArgs& a);

/// Registers --medium, --kind, --porosity, --width, ... in a "Medium" group. With
/// `fixed_count`, the medium is non-overlapping with --grains grains (the search's media) and
/// --kind/--porosity are not offered.
CLI::Option_group* add_medium_options(CLI::App* app, MediumArgs& a, bool fixed_count);
/// Registers the droplet's physical parameters (--masses, --nrt, ...) in a "Droplet" group.
CLI::Option_group* add_droplet_options(CLI::App* app, DropletParams& d);
/// The "Output" group of a command that prints a summary: --format (table or json), --json FILE
/// (the JSON summary written to a file too) and --quiet (no progress on stderr). The command adds
/// its own outputs to the group it returns.
CLI::Option_group* add_summary_options(CLI::App* app, std::string& format, std::string& json_file, bool& quiet);
/// A second droplet after the first (simulate, render animation): the release rule's name as given
/// (empty: one droplet) and the rest of its options.
struct SecondDropletArgs {
  std::string release;
  SecondDroplet second;
  bool given = false;  ///< --second-after or --second-offset-x was given
  bool on() const { return !release.empty(); }
};
/// Registers --second-droplet, --second-after and --second-offset-x in a "Two droplets" group.
CLI::Option_group* add_second_droplet_options(CLI::App* app, SecondDropletArgs& a);
/// Parses and checks them for `droplet`; throws std::invalid_argument naming the option (also for
/// --second-after or --second-offset-x without --second-droplet).
void check_second_droplet(SecondDropletArgs& a, const DropletParams& droplet);
/// Between walls, the second droplet's start (x0 + offset) must be inside them, and with an offset
/// x0 must be given; throws std::invalid_argument naming --second-offset-x.
void check_second_start(const SecondDropletArgs& a, double x0, const Medium& medium, const DropletParams& droplet);

/// Registers --max-steps, --stuck-window, --stuck-distance in `group`.
void add_exit_options(CLI::Option_group* group, RunOptions& r);

/// The check of a seed option: a whole decimal number in [0, 2^64 - 1] (a minus sign would wrap
/// around, and a larger number would saturate, silently).
CLI::Validator seed_check();
/// The check of an index option such as --generation: a whole decimal number >= 0.
CLI::Validator index_check();
/// The check of a count that must be given as >= 1 (--group, --trace-interval), where 0 is the
/// default's "not given".
CLI::Validator positive_check();
/// The check of a run or sweep id (--run, --resume, --sweep): a whole decimal number >= 1 (0 would
/// read as "not given").
CLI::Validator id_check();
/// The check of --x0: a finite number (NaN would read as "not given").
CLI::Validator finite_check();
/// Throws std::invalid_argument naming --x0 unless the droplet starts inside the box: x0 in
/// [0, width] when periodic, and the whole ring, [R, width - R], between solid walls.
void check_start_x(double x0, const Medium& medium, const DropletParams& droplet);

/// Most worker threads a command accepts (--threads; 0 means all cores).
using detail::kMaxThreads;
/// Throws std::invalid_argument unless 0 <= threads <= kMaxThreads.
void check_threads(int threads);

/// Most samples (path points, area samples, snapshot points) a command may keep in memory for
/// all its droplets together: about 2.4 GB.
constexpr double kMaxRecordedSamples = 1e8;
/// Throws std::invalid_argument naming the option if `droplets` droplets of `masses` masses could
/// record more than kMaxRecordedSamples samples with these run options (each can run max-steps).
void check_recording(const RunOptions& run, long droplets, int masses);

/// Parses the names into options.kind / radii / periodic and validates them (unless a file is
/// given); throws std::invalid_argument naming the bad parameter.
void resolve_medium(MediumArgs& a);

/// Throws std::invalid_argument naming `option` if a snapshot time lies after the last step a run
/// may take (max-steps x dt): no run could record it.
void check_snapshot_times(const std::vector<double>& times, const RunOptions& run, const DropletParams& droplet,
                          const std::string& option);

/// Throws std::invalid_argument naming the option if `command` was given --medium FILE together
/// with an option that shapes a generated medium (--porosity, --width, ...) among the command
/// line's `words`: the file fixes the medium, and the option would be ignored. A config file may
/// hold such options (the installed droplets' configs name their grains); optimize keeps --gap,
/// its moves' spacing rule.
void check_medium_file_alone(const CLI::App& command, const std::vector<std::string>& words);

}  // namespace softdrop::cli
