#include "cli/common_options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "cli/output.hpp"

namespace softdrop::cli {

CLI::Option_group* add_medium_options(CLI::App* s, MediumArgs& a, bool fixed_count) {
  auto* g = s->add_option_group("Medium", "generated unless --medium is given");
  if (fixed_count) {
    g->add_option("--medium", a.file, "Load the medium from this grain file (.json or .csv)");
    g->add_option("--grains", a.options.grains, "Number of non-overlapping grains")->capture_default_str();
  } else {
    g->add_option("--medium", a.file,
                  "Load the medium from this grain file (.json or .csv), or from a binary image (.png, .tif, .npy: "
                  "white, 1 or True is pore), whose solid the droplet meets through a signed distance field");
    g->add_option("--pixel-size", a.pixel_size, "An image medium's pixel side (length units)")->capture_default_str();
    g->add_option("--kind", a.kind,
                  "overlapping, non-overlapping (random sequential addition) or relaxed (non-overlapping, "
                  "placed at random and pushed apart: lower porosities with wider gaps)")
        ->capture_default_str()
        ->check(CLI::IsMember(medium_kind_names()));
    g->add_option("--porosity", a.options.porosity, "Target porosity phi, in (0, 1)")->capture_default_str();
  }
  g->add_option("--width", a.options.width, "Box width W (length units)")->capture_default_str();
  g->add_option("--height", a.options.height, "Box height H (length units)")->capture_default_str();
  g->add_option("--r-min", a.options.r_min, "Smallest grain radius (length units)")->capture_default_str();
  g->add_option("--r-max", a.options.r_max, "Largest grain radius (length units)")->capture_default_str();
  g->add_option("--radius-distribution", a.radii,
                "uniform in [r-min, r-max], or lognormal (--r-median, --r-sigma) cut to that range")
      ->capture_default_str()
      ->check(CLI::IsMember(radius_distribution_names()));
  g->add_option("--r-median", a.options.r_median, "Log-normal: median grain radius (length units)")
      ->capture_default_str();
  g->add_option("--r-sigma", a.options.r_sigma, "Log-normal: standard deviation of ln r")->capture_default_str();
  g->add_option("--gap", a.options.gap,
                fixed_count ? "Spacing rule: min surface gap as a fraction of the larger radius"
                            : "Non-overlapping and relaxed: min surface gap as a fraction of the larger radius")
      ->capture_default_str();
  g->add_flag("--walls", a.walls, "Solid side walls instead of periodic x");
  g->add_option("--medium-seed", a.options.seed, "Seed of the medium generator")
      ->capture_default_str()
      ->check(seed_check());
  if (fixed_count) a.kind = "non-overlapping";
  return g;
}

CLI::Option_group* add_summary_options(CLI::App* s, std::string& format, std::string& json_file, bool& quiet) {
  auto* o = s->add_option_group("Output");
  o->add_option("--format", format, "Summary on stdout: table or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "json"}));
  o->add_option("--json", json_file, "Also write the JSON summary to this file");
  o->add_flag("--quiet", quiet, "No progress on stderr");
  return o;
}

CLI::Option_group* add_droplet_options(CLI::App* s, DropletParams& d) {
  auto* g = s->add_option_group("Droplet", "physical parameters, paper's numerical units");
  // One option per field of the one list (droplet.hpp), with its help.
  visit_droplet_fields(
      [&](const DropletField& field, auto& value) {
        const std::string name = std::string("--") + field.key;
        if constexpr (std::is_enum_v<std::decay_t<decltype(value)>>) {
          g->add_option_function<std::string>(
               name, [&value](const std::string& v) { parse_name(v, &value); }, field.help)
              ->check(CLI::IsMember(value_names(value)))
              ->default_str(to_string(value));
        } else {
          g->add_option(name, value, field.help)->capture_default_str();
        }
      },
      d);
  return g;
}

void add_exit_options(CLI::Option_group* g, RunOptions& r) {
  g->add_option("--max-steps", r.max_steps, "Step budget per droplet (timeout)")->capture_default_str();
  g->add_option("--stuck-window", r.stuck_window, "Stuck test window (time units)")->capture_default_str();
  g->add_option("--stuck-distance", r.stuck_distance, "Downward progress required per window (length units)")
      ->capture_default_str();
  g->add_option("--rest-window", r.rest_window,
                "Rest test window (time units; 0: none): a droplet at rest is stuck without waiting for the stuck test")
      ->capture_default_str();
  g->add_option("--rest-distance", r.rest_distance,
                "Travel of the centre of mass, in any direction, below which a droplet is at rest (length units)")
      ->capture_default_str();
}

CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos)
          return "'" + v + "' is not a whole number in [0, 2^64 - 1]";
        errno = 0;
        std::strtoull(v.c_str(), nullptr, 10);
        if (errno == ERANGE) return "'" + v + "' is more than 2^64 - 1";
        return "";
      },
      "SEED");
}

CLI::Validator index_check() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos)
          return "'" + v + "' is not a whole number >= 0";
        return "";
      },
      "N");
}

namespace {
// A whole decimal number >= 1; `what` names what any other text is not.
CLI::Validator from_one(const std::string& what, const char* name) {
  return CLI::Validator(
      [what](std::string& v) -> std::string {
        const bool digits = !v.empty() && v.find_first_not_of("0123456789") == std::string::npos;
        return digits && v.find_first_not_of('0') != std::string::npos ? "" : "'" + v + "' is not " + what;
      },
      name);
}
}  // namespace

CLI::Validator positive_check() { return from_one("a whole number >= 1", "N"); }

CLI::Validator id_check() { return from_one("an id (ids are whole numbers from 1)", "ID"); }

CLI::Validator finite_check() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !std::isfinite(x)) return "'" + v + "' is not a finite number";
        return "";
      },
      "NUMBER");
}

void check_start_x(double x0, const Medium& medium, const DropletParams& droplet) {
  if (std::isnan(x0)) return;  // not given: the command picks the start
  const double lo = medium.periodic ? 0.0 : droplet.radius, hi = medium.width - lo;
  if (!(x0 >= lo && x0 <= hi))
    throw std::invalid_argument("x0 = " + fmt(x0) + ": the droplet must start inside the box, x0 in [" + fmt(lo) +
                                ", " + fmt(hi) + "]" + (medium.periodic ? "" : " (the whole ring between the walls)"));
}

void check_threads(int threads) {
  std::string why;
  if (!detail::valid_threads(threads, &why)) throw std::invalid_argument(why);
}

void check_recording(const RunOptions& run, long droplets, int masses) {
  const double steps = static_cast<double>(run.max_steps), n = static_cast<double>(droplets);
  auto check = [&](const char* option, int interval, const char* sample) {
    if (interval <= 0) return;
    const double samples = n * (steps / interval + 1);
    if (samples > kMaxRecordedSamples)
      throw std::invalid_argument(
          std::string(option) + " = " + std::to_string(interval) + ": " + std::to_string(droplets) +
          " droplets of up to " + std::to_string(run.max_steps) + " steps could keep " + fmt(samples, 3) + " " +
          sample + " in memory, more than the limit of 1e8; raise --" + option + " or lower --max-steps");
  };
  check("path-interval", run.path_interval, "path points");
  check("trace-interval", run.area_interval, "area samples");
  const double points = n * static_cast<double>(run.snapshot_times.size()) * masses;
  if (points > kMaxRecordedSamples)
    throw std::invalid_argument("snapshot-times: " + std::to_string(run.snapshot_times.size()) + " times for " +
                                std::to_string(droplets) + " droplets of " + std::to_string(masses) +
                                " masses would keep " + fmt(points, 3) +
                                " points in memory, more than the limit of 1e8");
}

Medium load_medium_file(const MediumArgs& a) {
  if (is_image_file(a.file)) return load_image_medium(a.file, a.pixel_size, !a.walls);
  return load_medium(a.file);
}

void resolve_medium(MediumArgs& a) {
  if (!a.file.empty()) return;
  a.options.kind = parse_medium_kind(a.kind);
  a.options.radii = parse_radius_distribution(a.radii);
  a.options.periodic = !a.walls;
  std::string why;
  if (!a.options.IsValid(&why)) throw std::invalid_argument(why);
}

void check_snapshot_times(const std::vector<double>& times, const RunOptions& run, const DropletParams& droplet,
                          const std::string& option) {
  const double end = static_cast<double>(run.max_steps) * droplet.dt;
  for (double t : times)
    if (!(t <= end))
      throw std::invalid_argument(option + ": " + fmt(t) +
                                  " is after the run's last step (max-steps x dt = " + fmt(end) + " time units)");
}

void check_medium_file_alone(const CLI::App& command, const std::vector<std::string>& words) {
  const auto on_command_line = [&](const std::string& name) {
    return std::any_of(words.begin(), words.end(),
                       [&](const std::string& w) { return w == name || w.rfind(name + "=", 0) == 0; });
  };
  const CLI::Option* file = command.get_option_no_throw("--medium");
  const bool image = file != nullptr && file->count() > 0 && is_image_file(file->as<std::string>());
  const CLI::Option* pixel = command.get_option_no_throw("--pixel-size");
  if (!image && pixel != nullptr && pixel->count() > 0 && on_command_line("--pixel-size"))
    throw std::invalid_argument(
        "pixel-size: has an effect only with an image --medium (.png, .tif, .npy); leave it out");
  if (file == nullptr || file->count() == 0) return;
  const bool search = command.get_name() == "optimize";  // its moves keep --gap with any medium
  for (const CLI::App* group :
       command.get_subcommands([](const CLI::App* s) { return s->get_name().empty() && s->get_group() == "Medium"; }))
    for (const CLI::Option* o : group->get_options())
      if (o != file && o->count() > 0 && on_command_line(o->get_name()) && !(search && o->get_name() == "--gap") &&
          !(image && (o == pixel || o->get_name() == "--walls")))
        throw std::invalid_argument(o->get_name().substr(2) +
                                    ": has no effect with --medium (the grain file fixes the "
                                    "medium); leave it out");
}

CLI::Option_group* add_second_droplet_options(CLI::App* app, SecondDropletArgs& a) {
  auto* t = app->add_option_group("Two droplets", "a second droplet pushed after each");
  t->add_option("--second-droplet", a.release,
                "Release a second droplet after the first: distance (once the first's centre is --second-after "
                "below its start) or delay (--second-after time units after the first began)");
  const auto given = [&a](const std::string&) { a.given = true; };
  t->add_option("--second-after", a.second.after,
                "The release's descent of the first (length units) or delay (time units)")
      ->capture_default_str()
      ->each(given);
  t->add_option("--second-offset-x", a.second.offset_x, "The second's start x minus the first's (length units)")
      ->capture_default_str()
      ->each(given);
  return t;
}

void check_second_droplet(SecondDropletArgs& a, const DropletParams& droplet) {
  if (!a.on()) {
    if (a.given) throw std::invalid_argument("second-after, second-offset-x: have no effect without --second-droplet");
    return;
  }
  a.second.release = parse_second_release(a.release);
  std::string why;
  if (!a.second.IsValid(droplet, &why)) throw std::invalid_argument(why);
}

void check_second_start(const SecondDropletArgs& a, double x0, const Medium& medium, const DropletParams& droplet) {
  if (!a.on() || medium.periodic || a.second.offset_x == 0) return;
  const double R = droplet.radius, W = medium.width, x1 = x0 + a.second.offset_x;
  if (std::isnan(x0))
    throw std::invalid_argument(
        "second-offset-x: between walls it needs --x0 (a random start could put the second droplet outside them)");
  if (x1 < R || x1 > W - R)
    throw std::invalid_argument("second-offset-x = " + fmt(a.second.offset_x) +
                                ": the second droplet's start x = " + fmt(x1) + " is not within the walls, [R, W - R]");
}

}  // namespace softdrop::cli
