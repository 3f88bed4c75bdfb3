// softdrop.simulate_pair and simulate_pairs: two droplets one after the other (simulation.hpp),
// each droplet's run as simulate gives it, with the pair's release and contacts.
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "cli/common_options.hpp"
#include "softdrop/batch.hpp"

namespace softdrop::python {
namespace {

// A message of the library's about the pair's settings, with Python's keywords for the program's
// options: release (--second-droplet), after (--second-after), offset_x (--second-offset-x).
std::string pair_words(std::string message) {
  static const std::pair<std::string, std::string> kNames[] = {
      {"second-droplet", "release"}, {"second-after", "after"}, {"second-offset-x", "offset_x"}};
  for (const auto& [option, keyword] : kNames)
    for (std::size_t at = message.find(option); at != std::string::npos; at = message.find(option, at))
      message.replace(at, option.size(), keyword);
  return message;
}

SecondDroplet second_droplet(const std::string& release, double after, double offset_x, const DropletParams& params) {
  try {
    SecondDroplet s;
    s.release = parse_second_release(release);
    s.after = after, s.offset_x = offset_x;
    std::string why;
    if (!s.IsValid(params, &why)) throw std::invalid_argument(why);
    return s;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(pair_words(e.what()));
  }
}

// One droplet of a pair: its run, and when it was first held.
py::dict droplet_dict(const RunSummary& s, double held_at, bool path, bool trace) {
  py::dict d = summary_dict(s, path);
  d["held_at"] = held_at;
  if (trace) {  // rows of time, area, every trace_interval steps of its own run
    py::array_t<double> rows({static_cast<py::ssize_t>(s.area_t.size()), py::ssize_t{2}});
    auto v = rows.mutable_unchecked<2>();
    for (std::size_t i = 0; i < s.area_t.size(); ++i) {
      const auto k = static_cast<py::ssize_t>(i);
      v(k, 0) = s.area_t[i], v(k, 1) = s.area[i];
    }
    d["trace"] = rows;
  }
  return d;
}

py::dict pair_dict(const TwoDropletSummary& p, bool path, bool trace) {
  py::dict d;
  d["first"] = droplet_dict(p.first, p.first_held_at, path, trace);
  d["second"] = droplet_dict(p.second, p.second_held_at, path, trace);
  d["released"] = p.released;
  d["released_at"] = p.released_at;
  d["contact_steps"] = p.contact_steps;
  d["shared_touched"] = p.shared_touched;
  return d;
}

}  // namespace

void bind_two_droplets(py::module_& m) {
  m.def(
      "_simulate_pair",
      [](const Medium& medium, double x0, const std::string& release, double after, double offset_x,
         const DropletParams& params, const RunOptions& run, bool path, int trace_interval) {
        check(params, run);
        if (!(x0 >= 0 && x0 <= medium.width))
          throw std::invalid_argument("x0 = " + std::string(py::repr(py::float_(x0))) + ": must be in [0, width]");
        const SecondDroplet second = second_droplet(release, after, offset_x, params);
        RunOptions options = run;
        if (path && options.path_interval == 0) options.path_interval = 100;
        options.area_interval = trace_interval;
        bool interrupted = false;
        TwoDropletSummary p;
        {
          py::gil_scoped_release unlocked;
          try {
            p = run_two_droplets(params, medium, x0, interruptible(options, &interrupted), second);
          } catch (const RunCancelled&) {
          }
        }
        if (interrupted) throw py::error_already_set();
        return pair_dict(p, path, trace_interval > 0);
      },
      py::arg("medium"), py::arg("x0"), py::arg("release"), py::arg("after"), py::arg("offset_x"), py::arg("params"),
      py::arg("run"), py::arg("path"), py::arg("trace_interval"));

  m.def(
      "_simulate_pairs",
      [](const Medium& medium, int pairs, std::uint64_t seed, int threads, const std::string& release, double after,
         double offset_x, const DropletParams& params, const RunOptions& run) {
        check(params, run);
        if (pairs < 1 || pairs > 10'000'000)
          throw std::invalid_argument("n = " + std::to_string(pairs) + ": must be in [1, 1e7]");
        cli::check_threads(threads);
        const SecondDroplet second = second_droplet(release, after, offset_x, params);
        if (!medium.periodic && offset_x != 0)
          throw std::invalid_argument(
              "offset_x: between walls, random starts could put the second droplet outside "
              "them; use simulate_pair with x0");
        BatchOptions batch;
        batch.droplets = pairs, batch.seed = seed, batch.threads = threads;
        const auto progress = stop_on_ctrl_c();
        std::vector<TwoDropletSummary> out;
        {
          py::gil_scoped_release unlocked;
          out = run_two_droplet_batch(params, medium, run, batch, second, progress);
        }
        py::list rows;
        for (const TwoDropletSummary& p : out) rows.append(pair_dict(p, false, false));
        return rows;
      },
      py::arg("medium"), py::arg("n"), py::arg("seed"), py::arg("threads"), py::arg("release"), py::arg("after"),
      py::arg("offset_x"), py::arg("params"), py::arg("run"));
}

}  // namespace softdrop::python
