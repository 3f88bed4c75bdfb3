// `softdrop render`: its seven subcommands and their options (the drawing is render_command.cpp's,
// render_paths.cpp's, render_search.cpp's and render_curves.cpp's).
#include "cli/common_options.hpp"
#include "cli/render_command.hpp"

namespace softdrop::cli {

CLI::App* add_render_command(CLI::App& app, RenderArgs& a) {
  CLI::App* r = app.add_subcommand(
      "render", "Draw media, droplets, paths, searches and animations (PNG, SVG, PDF; animations GIF or MP4)");
  r->require_subcommand(1);
  r->fallthrough();  // lets `render medium --config FILE` reach the program-level --config
  auto style = [&](CLI::App* s, const char* formats) {
    s->fallthrough();
    auto* g = s->add_option_group("Picture");
    g->add_option("--output,-o", a.output, std::string("Picture file: ") + formats + " (format from the extension)")
        ->required();
    g->add_option("--size", a.size, "Width in points (1/72 inch; pixels at --dpi 72); the height follows")
        ->capture_default_str();
    g->add_option("--dpi", a.dpi, "PNG resolution: pixels an inch (300 for print)")->capture_default_str();
    g->add_option("--background", a.background, "Colour #rrggbb[aa]")->capture_default_str();
    g->add_option("--grain-colour", a.grain_colour, "Grain outline colour")->capture_default_str();
    g->add_option("--touched-colour", a.touched_colour, "Fill of grains the droplet touched")->capture_default_str();
    g->add_option("--path-colour", a.path_colour, "Centre-of-mass path colour")->capture_default_str();
    g->add_option("--droplet-colour", a.droplet_colour, "Droplet boundary colour")->capture_default_str();
    g->add_flag("--no-caption", a.no_caption, "No line of text under the picture");
    g->add_flag("--scale-bar", a.scale_bar, "A labelled bar of a round length at the lower left of the box");
    g->add_flag("--quiet", a.quiet, "No progress on stderr (the droplets of paths, an animation's frames)");
  };
  auto scene_options = [&](CLI::App* s) {
    add_medium_options(s, a.medium, false);
    auto* d = add_droplet_options(s, a.droplet);
    add_exit_options(d, a.run);
  };

  CLI::App* m = r->add_subcommand("medium", "The grains as outlined discs, with periodic copies at the edges");
  style(m, ".png, .svg or .pdf");
  add_medium_options(m, a.medium, false);

  CLI::App* s = r->add_subcommand("snapshots", "The droplet's boundary at chosen times over the medium (paper Fig. 2)");
  style(s, ".png, .svg or .pdf");
  scene_options(s);
  s->add_option("--x0", a.x0, "Start x of the droplet centre (default: the middle)")->check(finite_check());
  s->add_option("--times", a.times, "Times of the snapshots (time units), comma-separated")->delimiter(',')->required();

  CLI::App* p = r->add_subcommand("paths", "Centre-of-mass paths of many droplets, alpha-blended");
  style(p, ".png, .svg or .pdf");
  scene_options(p);
  p->add_option("--droplets", a.batch.droplets, "Droplets from random starts")->capture_default_str();
  p->add_option("--seed", a.batch.seed, "Seed of the start positions")->capture_default_str()->check(seed_check());
  p->add_option("--threads", a.batch.threads, "Worker threads (0 = all cores)")->capture_default_str();
  p->add_option("--stuck-colour", a.stuck_colour, "Path colour of droplets that did not pass")->capture_default_str();
  p->add_option("--alpha", a.alpha, "Opacity of one path (0: automatic, 10 / droplets, at least 0.03)")
      ->capture_default_str();
  p->add_option("--path-interval", a.path_interval, "Steps between recorded points of a path")->capture_default_str();

  CLI::App* q = r->add_subcommand(
      "search", "A search's best arrangement with droplets' paths through it, its T in the search and held out");
  style(q, ".png, .svg or .pdf");
  q->add_option("--db", a.db, "SQLite history file")->required();
  q->add_option("--run", a.run_id, "Run id")->required()->check(id_check());
  q->add_option("--generation", a.generation, "The best as of this generation (default: the run's best)")
      ->check(index_check());
  q->add_option("--curve", a.curve,
                "Also draw the best's T against generation to this file, in the search and held out");
  q->add_option("--droplets", a.search_droplets,
                "Paths of the first N random starts of the best's held-out value, touched grains filled "
                "(default: 50 for a robust objective; 0 for single, which draws its droplet from x0 = W/2 thick "
                "and the earlier bests' thin)");

  CLI::App* v = r->add_subcommand(
      "animation", "A droplet pushed through the medium, as an animated GIF or an MP4 video (.gif, .mp4)");
  style(v, ".gif");
  scene_options(v);
  v->add_option("--x0", a.x0, "Start x of the droplet centre (default: the middle)")->check(finite_check());
  v->add_option("--fps", a.fps, "Frames per second")->capture_default_str();
  v->add_option("--speed", a.speed, "Simulated time units per second of animation (1 = real time)")
      ->capture_default_str();
  v->add_option("--max-frames", a.max_frames, "Refuse animations longer than this")->capture_default_str();
  add_second_droplet_options(v, a.second);
  CLI::App* t =
      r->add_subcommand("trace", "The area trace S(t)/S0 of one droplet, entry and exit marked (paper's area figure)");
  style(t, ".png, .svg or .pdf");
  scene_options(t);
  t->add_option("--x0", a.x0, "Start x of the droplet centre (default: the middle)")->check(finite_check());
  t->add_option("--csv", a.csv, "Also write the samples (droplet, t, area, area_ratio, phase) to this CSV");

  CLI::App* c =
      r->add_subcommand("curves", "The best T of several searches against evaluations (or seconds), one line each");
  style(c, ".png, .svg or .pdf");
  c->add_option("--db", a.dbs, "A search's SQLite history (repeat for more searches)")->required();
  c->add_option("--run", a.run_id, "Run id in every file (default: each file's only run)")->check(id_check());
  c->add_option("--label", a.labels,
                "Legend label, one a --db in order (default: the file name without a trailing -<seed>; "
                "equal labels share a colour)");
  c->add_option("--x", a.x_axis, "evaluations or seconds (wall, summed over generations)")
      ->capture_default_str()
      ->check(CLI::IsMember({"evaluations", "seconds"}));
  return r;
}

}  // namespace softdrop::cli
