#include "cli/tortuosity_command.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "cli/output.hpp"
#include "cli/simulate_output.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/render.hpp"
#include "softdrop/simulation.hpp"
#include "softdrop/version.hpp"
#include "studies/pore_tortuosity.hpp"

namespace softdrop::cli {

namespace {
// The least pixels a radius of the smallest grain: below it a throat between two grains is a few
// pixels wide, and the first-order error of the solves is tens of percent.
constexpr double kMinPixelsPerRadius = 4;
}  // namespace

CLI::App* add_tortuosity_command(CLI::App& app, TortuosityArgs& a) {
  CLI::App* s = app.add_subcommand(
      "tortuosity",
      "A medium's tortuosities side by side: the droplet's, and its pore space's on a pixel image (geometric: "
      "shortest paths; diffusive: tau = phi D / D_eff; hydrodynamic: <|u|> / <-u_y> of creeping flow, with the "
      "permeability), each at a resolution and its double");
  s->fallthrough();
  add_medium_options(s, a.medium, false);
  auto* g = s->add_option_group("Tortuosity");
  g->add_option("--pixels", a.pixels,
                "Pixels across the box's width at the coarser resolution; the finer has twice as many (the pixel "
                "count of the height follows). An image medium: its own columns unless given")
      ->capture_default_str()
      ->each([&a](const std::string&) { a.pixels_given = true; });
  g->add_option("--starts", a.droplets.starts, "Droplets from random starts for the droplet's T (0: none)")
      ->capture_default_str();
  g->add_option("--seed", a.droplets.seed, "Seed of the droplets' starts")->capture_default_str()->check(seed_check());
  g->add_flag("--flow,!--no-flow", a.flow,
              "Solve the creeping flow for the hydrodynamic T and the permeability (the slowest part: --no-flow "
              "leaves it out)");
  g->add_option("--threads", a.droplets.threads, "Worker threads for the droplets (0 = all cores)")
      ->capture_default_str();
  auto* d = add_droplet_options(s, a.droplet);
  add_exit_options(d, a.run);
  auto* o = add_summary_options(s, a.format, a.json_file, a.quiet);
  o->add_option("--csv", a.csv_file,
                "CSV, one row a value: quantity (geometric_tortuosity, diffusive_tortuosity, hydrodynamic_tortuosity, "
                "permeability, droplet_tortuosity), pixels (empty: extrapolated or the droplet's), pixel (length "
                "units), value, standard_error");
  o->add_option("--picture", a.picture,
                "Draw the pore space at the coarser resolution: the diffusion's concentration and shortest paths "
                "(.png, .svg or .pdf)");
  o->add_option("--flow-picture", a.flow_picture,
                "Draw the flow at the coarser resolution: its speed and shortest paths (.png, .svg or .pdf)");
  o->add_option("--size", a.size, "The picture's width in points")->capture_default_str();
  return s;
}

void check_tortuosity(TortuosityArgs& a) {
  resolve_medium(a.medium);
  if (a.pixels < 8 || a.pixels > 4000)
    throw std::invalid_argument("pixels = " + std::to_string(a.pixels) + ": must be in [8, 4000]");
  a.droplets.half_dt = false;
  std::string why;
  if (a.droplets.starts != 0 && !a.droplets.IsValid(&why)) throw std::invalid_argument(why);
  if (!a.droplet.IsValid(&why)) throw std::invalid_argument(why);
  if (!a.run.IsValid(&why)) throw std::invalid_argument(why);
  for (const auto& [option, path] : {std::pair{"--json", a.json_file}, {"--csv", a.csv_file}})
    if (!path.empty()) check_output_path(option, path);
  if (!a.picture.empty()) check_picture_path("--picture", a.picture);
  if (!a.flow_picture.empty()) check_picture_path("--flow-picture", a.flow_picture);
  if (!a.flow && !a.flow_picture.empty())
    throw std::invalid_argument("flow-picture: needs the flow (--no-flow was given)");
  if (a.size < 100 || a.size > 5000)
    throw std::invalid_argument("size = " + std::to_string(a.size) + ": must be in [100, 5000]");
}

namespace {

struct Resolved {
  int pixels;
  double pixel;
  PoreImage image;
  GeometricTortuosity geometric;
  DiffusiveTortuosity diffusive;
  HydrodynamicTortuosity flow;  // empty without --flow
};

// The tortuosities at `pixels` across; a medium with no pore path says so in one line.
Resolved at_resolution(const Medium& m, int pixels, bool flow, bool quiet) {
  if (!quiet)
    std::cerr << "tortuosity: the pore space at " << pixels << " pixels across" << (flow ? " (with the flow)" : "")
              << "\n";
  const PoreImage image = pore_image(m, pixels);
  try {
    return {pixels,
            image.pixel,
            image,
            geometric_tortuosity(image),
            diffusive_tortuosity(image),
            flow ? hydrodynamic_tortuosity(image) : HydrodynamicTortuosity{}};
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("tortuosity: the medium at " + std::to_string(pixels) + " pixels across: " + e.what() +
                             "; every tortuosity is undefined");
  }
}

nlohmann::json pair_json(double coarse, double fine, int pixels) {
  return {{"pixels", {pixels, 2 * pixels}},
          {"values", {coarse, fine}},
          {"change", (fine - coarse) / coarse},
          {"extrapolated", 2 * fine - coarse}};
}

std::string pair_line(double coarse, double fine, int pixels) {
  return fmt(coarse, 5) + " at " + std::to_string(pixels) + " px, " + fmt(fine, 5) + " at " +
         std::to_string(2 * pixels) + " px (" + (fine >= coarse ? "+" : "") + fmt(100 * (fine - coarse) / coarse, 2) +
         " %), extrapolated " + fmt(2 * fine - coarse, 5);
}

// A pore field of resolution `r` drawn under the grains (their solid union, as the solves saw it)
// from `lo` (dark blue) to `hi` (yellow), with 24 shortest paths from starts spread over the top.
// `what` names the field; the caption adds the paths and `values`.
void draw_field(const Medium& medium, const Resolved& r, const Field& field, const std::string& what,
                const std::string& values, int size, const std::string& path) {
  const std::string caption =
      what + " and 24 shortest paths at " + std::to_string(r.pixels) + " pixels across: " + values;
  Scene scene;
  scene.medium = medium;
  scene.field = field;
  for (const PorePath& p : shortest_paths(r.image, r.geometric, 24))
    scene.lines.push_back({p.x, p.y, Rgba{1, 1, 1, 0.9}, 1.2});
  scene.caption = caption;
  scene.top_room = 0;
  RenderStyle style;
  style.width = size;
  style.solid_grains = true;
  render_scene(scene, style, path);
}

// The pictures: the diffusion's concentration (0 at the bottom, 1 at the top), and the flow's
// speed |u| from 0 to its largest.
void draw_pictures(const Medium& medium, const Resolved& r, const TortuosityArgs& a) {
  if (!a.picture.empty())
    draw_field(
        medium, r, {r.image.nx, r.image.ny, r.diffusive.concentration, 0, 1}, "diffusion (concentration, 0 to 1)",
        "tau = " + fmt(r.diffusive.tau, 4) + ", geometric T = " + fmt(r.geometric.tortuosity, 4), a.size, a.picture);
  if (a.flow_picture.empty()) return;
  std::vector<double> speed(r.flow.ux.size());
  double top = 0;
  for (std::size_t k = 0; k < speed.size(); ++k) {
    speed[k] = std::hypot(r.flow.ux[k], r.flow.uy[k]);  // NaN in the solid
    if (speed[k] > top) top = speed[k];
  }
  draw_field(
      medium, r, {r.image.nx, r.image.ny, speed, 0, top > 0 ? top : 1}, "creeping flow (speed, 0 to its largest)",
      "hydrodynamic T = " + fmt(r.flow.tortuosity, 4) + ", k = " + fmt(r.flow.permeability, 4), a.size, a.flow_picture);
}

}  // namespace

int tortuosity_pixels(const TortuosityArgs& a, const Medium& medium) {
  return medium.image && !a.pixels_given ? medium.image->nx : a.pixels;
}

double check_resolution(const Medium& medium, int pixels) {
  double r_min = medium.width;
  for (const Grain& g : medium.grains) r_min = std::min(r_min, g.r);
  const double per_radius = r_min / (medium.width / pixels);
  if (!medium.grains.empty() && per_radius < kMinPixelsPerRadius)
    throw std::invalid_argument("pixels = " + std::to_string(pixels) + ": " + fmt(per_radius, 3) +
                                " pixels a radius of the smallest grain (r = " + fmt(r_min) + "), fewer than 4");
  return per_radius;
}

int run_tortuosity(TortuosityArgs& a) {
  check_tortuosity(a);
  const Medium medium = a.medium.file.empty() ? generate_medium(a.medium.options) : load_medium_file(a.medium);
  const int pixels = tortuosity_pixels(a, medium);
  const double per_radius = check_resolution(medium, pixels);
  // A droplet the medium refuses (a speck or grain smaller than an edge) is refused before the
  // solves, not after them.
  if (a.droplets.starts > 0) try {
      (void)Simulation(a.droplet, medium);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) + " (--starts 0: the pore space's tortuosities alone)");
    }
  const Resolved coarse = at_resolution(medium, pixels, a.flow, a.quiet);
  const Resolved fine = at_resolution(medium, 2 * pixels, a.flow, a.quiet);
  HeldOutValue droplets;
  if (a.droplets.starts > 0) {
    Progress progress("tortuosity: droplets");
    droplets = held_out_value(a.droplet, medium, a.run, a.droplets, [&](int done, int total) {
      if (!a.quiet) progress.update(done, total);
    });
  }
  const HeldOutRuns& d = droplets.at_dt;
  nlohmann::json j{{"version", kVersion},
                   {"medium", medium_record(medium, exact_porosity(medium))},
                   {"pixels_per_smallest_radius",
                    medium.grains.empty() ? nlohmann::json() : nlohmann::json({per_radius, 2 * per_radius})},
                   {"image_porosity", {coarse.diffusive.porosity, fine.diffusive.porosity}},
                   {"geometric_tortuosity", pair_json(coarse.geometric.tortuosity, fine.geometric.tortuosity, pixels)},
                   {"diffusive_tortuosity", pair_json(coarse.diffusive.tau, fine.diffusive.tau, pixels)}};
  j["geometric_tortuosity"]["starts"] = fine.geometric.starts;
  j["geometric_tortuosity"]["connected"] = fine.geometric.connected;
  j["diffusive_tortuosity"]["formation_factor"] = {coarse.diffusive.formation_factor, fine.diffusive.formation_factor};
  if (a.flow) {
    j["hydrodynamic_tortuosity"] = pair_json(coarse.flow.tortuosity, fine.flow.tortuosity, pixels);
    j["hydrodynamic_tortuosity"]["buffer_rows"] = {coarse.flow.buffer_rows, fine.flow.buffer_rows};
    j["permeability"] = pair_json(coarse.flow.permeability, fine.flow.permeability, pixels);
  }
  if (a.droplets.starts > 0)
    j["droplet_tortuosity"] = {{"starts", d.starts},
                               {"seed", a.droplets.seed},
                               {"passed", d.passed},
                               {"mean_tortuosity", finite_or_null(d.mean_t)},
                               {"standard_error", finite_or_null(d.standard_error)}};
  draw_pictures(medium, coarse, a);
  if (!a.json_file.empty()) write_file_atomically(a.json_file, j.dump(2) + "\n");
  if (!a.csv_file.empty()) {
    std::ostringstream out;
    out << "quantity,pixels,pixel,value,standard_error\n";
    for (const Resolved* r : {&coarse, &fine}) {
      out << "geometric_tortuosity," << r->pixels << ',' << fmt(r->pixel) << ',' << fmt(r->geometric.tortuosity) << ','
          << fmt(r->geometric.standard_error) << '\n';
      out << "diffusive_tortuosity," << r->pixels << ',' << fmt(r->pixel) << ',' << fmt(r->diffusive.tau) << ",\n";
      if (a.flow)
        out << "hydrodynamic_tortuosity," << r->pixels << ',' << fmt(r->pixel) << ',' << fmt(r->flow.tortuosity)
            << ",\npermeability," << r->pixels << ',' << fmt(r->pixel) << ',' << fmt(r->flow.permeability) << ",\n";
    }
    out << "geometric_tortuosity,,," << fmt(2 * fine.geometric.tortuosity - coarse.geometric.tortuosity) << ",\n";
    out << "diffusive_tortuosity,,," << fmt(2 * fine.diffusive.tau - coarse.diffusive.tau) << ",\n";
    if (a.flow)
      out << "hydrodynamic_tortuosity,,," << fmt(2 * fine.flow.tortuosity - coarse.flow.tortuosity)
          << ",\npermeability,,," << fmt(2 * fine.flow.permeability - coarse.flow.permeability) << ",\n";
    if (a.droplets.starts > 0 && d.passed > 0)
      out << "droplet_tortuosity,,," << fmt(d.mean_t) << ',' << (d.passed > 1 ? fmt(d.standard_error) : "") << '\n';
    write_file_atomically(a.csv_file, out.str());
  }
  if (a.format == "json") {
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << medium_line(medium, exact_porosity(medium)) << "image        " << pixels << " and " << 2 * pixels
            << " pixels across";
  if (!medium.grains.empty())
    std::cout << " (" << fmt(per_radius, 3) << " and " << fmt(2 * per_radius, 3) << " a smallest radius)";
  std::cout << ", porosity " << fmt(coarse.diffusive.porosity, 5) << " and " << fmt(fine.diffusive.porosity, 5) << "\n"
            << "geometric T  " << pair_line(coarse.geometric.tortuosity, fine.geometric.tortuosity, pixels) << "; "
            << fine.geometric.connected << " of " << fine.geometric.starts << " top pixels reach the bottom\n"
            << "diffusive    tau = " << pair_line(coarse.diffusive.tau, fine.diffusive.tau, pixels) << "\n";
  if (a.flow)
    std::cout << "flow T       " << pair_line(coarse.flow.tortuosity, fine.flow.tortuosity, pixels) << "\n"
              << "permeability " << pair_line(coarse.flow.permeability, fine.flow.permeability, pixels)
              << " (length units squared)\n";
  if (a.droplets.starts > 0) {
    std::cout << "droplet T    ";
    if (d.passed == 0)
      std::cout << "no droplet passed";
    else
      std::cout << "<T> = " << fmt(d.mean_t, 5) << (d.passed > 1 ? " +- " + fmt(d.standard_error, 2) : std::string());
    std::cout << "; " << d.passed << " of " << d.starts << " starts passed (seed " << a.droplets.seed << ")\n";
  }
  return 0;
}

}  // namespace softdrop::cli
