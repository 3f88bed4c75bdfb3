// The `softdrop` Python module's compiled core (`softdrop._core`): media, droplets and runs on the
// same libraries as the command line, so the same inputs give the same bits. Long runs release
// the GIL and stop on Ctrl-C (KeyboardInterrupt). Bad arguments raise ValueError with the
// library's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "arguments.hpp"
#include "bindings.hpp"
#include "cli/columns.hpp"
#include "cli/common_options.hpp"
#include "media/rigid_descent.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"
#include "softdrop/version.hpp"
#include "studies/area_trace.hpp"
#include "values.hpp"

namespace py = pybind11;
using namespace softdrop;
namespace cli = softdrop::cli;
using softdrop::python::bind_commands;
using softdrop::python::bind_held_out;
using softdrop::python::bind_stores;
using softdrop::python::stop_on_ctrl_c;

namespace {

// Sets the attributes named by keyword arguments, refusing a name the object does not have.
void set_keywords(py::object self, const py::kwargs& kwargs) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (!py::hasattr(self, name.c_str()))
      throw std::invalid_argument(name + ": not a parameter of " +
                                  std::string(py::str(self.get_type().attr("__name__"))));
    py::setattr(self, name.c_str(), value);
  }
}

// The defaults with the attributes named by keyword arguments set: T(masses=30, ...).
template <class T>
T from_keywords(const py::kwargs& kwargs) {
  py::object object = py::cast(T{});
  set_keywords(object, kwargs);
  return object.cast<T>();
}

// "name (type, default value): help" for each attribute, a line each, as read from `defaults`: the
// keyword arguments' documentation of an __init__(**kwargs).
std::string keyword_lines(const py::object& defaults, const std::vector<std::pair<std::string, std::string>>& fields) {
  std::string out;
  for (const auto& [name, help] : fields) {
    const py::object v = defaults.attr(name.c_str());
    out += "    " + name + " (" + std::string(py::str(v.get_type().attr("__name__"))) + ", default " +
           std::string(py::repr(v)) + "): " + help + "\n";
  }
  return out;
}

// RunOptions' attributes, each read and written as its member, with its meaning.
const std::vector<std::pair<std::string, std::string>> kRunFields = {
    {"max_steps", "the step budget: a run not ended after this many steps is a timeout"},
    {"stuck_window", "the stuck test's window (time units)"},
    {"stuck_distance", "the downward progress the stuck test asks per window (length units)"},
    {"rest_window", "the rest test's window (time units; 0: no rest test)"},
    {"rest_distance",
     "a centre that travels less than this within rest_window is at rest, and the run ends stuck (length units)"},
    {"path_interval", "record the centre's path every this many steps (0: no path)"},
};

void bind_run_fields(py::class_<RunOptions>& cls) {
  const auto field = [&](const std::string& name, auto member) {
    using T = std::decay_t<decltype(std::declval<RunOptions&>().*member)>;
    std::string help;
    for (const auto& f : kRunFields)
      if (f.first == name) help = f.second;
    cls.def_property(
        name.c_str(), [member](const RunOptions& o) { return o.*member; },
        [member, name](RunOptions& o, const py::object& v) { o.*member = python::number_arg<T>(v, name.c_str()); },
        help.c_str());
  };
  field("max_steps", &RunOptions::max_steps);
  field("stuck_window", &RunOptions::stuck_window);
  field("stuck_distance", &RunOptions::stuck_distance);
  field("rest_window", &RunOptions::rest_window);
  field("rest_distance", &RunOptions::rest_distance);
  field("path_interval", &RunOptions::path_interval);
}

// One attribute per field of the one list (droplet.hpp), named as its option with '_' for '-',
// with its help as the docstring; the constraint order as its name ("sequential", "red-black").
template <class Field>
using Value = std::decay_t<Field>;
void bind_droplet_fields(py::class_<DropletParams>& cls) {
  DropletParams defaults;
  visit_droplet_fields(
      [&](const DropletField& field, const auto& proto) {
        using T = Value<decltype(proto)>;
        const std::string name = cli::column_name(field.key);
        const std::string key = field.key;
        // The field `key` of p, for reading or writing.
        auto with_field = [key](auto& p, const auto& use) {
          visit_droplet_fields(
              [&](const DropletField& f, auto& v) {
                if constexpr (std::is_same_v<Value<decltype(v)>, T>)
                  if (key == f.key) use(v);
              },
              p);
        };
        if constexpr (std::is_enum_v<T>) {
          cls.def_property(
              name.c_str(),
              [with_field](const DropletParams& p) {
                std::string out;
                with_field(p, [&](const T& v) { out = to_string(v); });
                return out;
              },
              [with_field, name](DropletParams& p, const py::object& v) {
                const std::string text = python::text_arg(v, name.c_str());
                with_field(p, [&](T& f) { parse_name(text, &f); });
              },
              field.help);
        } else {
          cls.def_property(
              name.c_str(),
              [with_field](const DropletParams& p) {
                T out{};
                with_field(p, [&](const T& v) { out = v; });
                return out;
              },
              [with_field, name](DropletParams& p, const py::object& v) {
                const T value = python::number_arg<T>(v, name.c_str());
                with_field(p, [&](T& f) { f = value; });
              },
              field.help);
        }
      },
      defaults);
}

}  // namespace

namespace softdrop::python {

void check(const DropletParams& params, const RunOptions& run) {
  std::string why;
  if (!params.IsValid(&why) || !run.IsValid(&why)) throw std::invalid_argument(why);
}

RunOptions interruptible(RunOptions run, bool* interrupted) {
  run.cancelled = [interrupted] {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      *interrupted = true;
      return true;
    }
    return false;
  };
  return run;
}

py::dict summary_dict(const RunSummary& s, bool with_path) {
  py::dict d;
  d["outcome"] = to_string(s.outcome);
  d["reason"] = s.reason;
  d["tortuosity"] = s.outcome == Outcome::passed ? s.tortuosity : std::numeric_limits<double>::quiet_NaN();
  d["route_tortuosity"] = s.outcome == Outcome::passed ? s.route_tortuosity : std::numeric_limits<double>::quiet_NaN();
  d["steps"] = s.steps;
  d["start_x"] = s.start_x;
  d["touched"] = s.touched.size();
  d["touched_grains"] = s.touched;
  d["min_area_ratio"] = s.min_area_ratio;
  d["max_penetration"] = s.max_penetration;
  d["shaken_at"] = s.shaken_at;  // NaN: the medium never shook
  if (with_path) {               // rows of x, y as every path softdrop gives, and their times beside them
    d["path"] = python::xy_array(s.path_x, s.path_y);
    d["path_time"] = py::array_t<double>(static_cast<py::ssize_t>(s.path_t.size()), s.path_t.data());
  }
  return d;
}

}  // namespace softdrop::python

using softdrop::python::check;
using softdrop::python::interruptible;
using softdrop::python::summary_dict;

PYBIND11_MODULE(_core, m) {
  m.doc() = "softdrop's compiled core; use the softdrop package";
  m.attr("__version__") = kVersion;

  py::class_<DropletParams> droplet(m, "DropletParams",
                                    "The droplet, in the paper's numerical units (see docs/model.md)");
  droplet.def_static("balloon", &DropletParams::balloon,
                     "The balloon: the droplet held at its stretch limit, as results/calibration/balloon.toml "
                     "(whose grains, radii 8 to 16, go to Medium.generate)");
  droplet.def_static("explicit_step", &DropletParams::explicit_step,
                     "The defaults' droplet with the explicit viscosity step (the reference) at the dt it needs, "
                     "3.5e-6, as results/calibration/explicit.toml");
  droplet.def_static("exponential_step", &DropletParams::exponential_step,
                     "The droplet calibrated for the exponential viscosity step, nu = 2.8e5 at dt = 6e-6, as "
                     "results/calibration/exponential.toml; not converged in dt (results/calibration/README.md)");
  droplet.def_static("passage", &DropletParams::passage,
                     "A smaller droplet with a stiffer ring, for more passage at low porosity, as "
                     "results/calibration/passage.toml (whose grains, radii 26 to 50, go to Medium.generate)");
  bind_droplet_fields(droplet);
  std::vector<std::pair<std::string, std::string>> droplet_docs;  // each attribute's name and meaning
  DropletParams defaults;
  visit_droplet_fields(
      [&](const DropletField& f, const auto&) { droplet_docs.emplace_back(cli::column_name(f.key), f.help); },
      defaults);
  std::vector<std::string> droplet_fields;
  for (const auto& field : droplet_docs) droplet_fields.push_back(field.first);
  python::def_value_semantics(droplet, droplet_fields, "DropletParams");
  const std::string droplet_init =
      "The defaults' droplet, with the parameters given as keywords set (another name raises ValueError, a wrong "
      "type TypeError):\n" +
      keyword_lines(py::cast(DropletParams{}), droplet_docs);
  droplet.def(py::init(&from_keywords<DropletParams>), droplet_init.c_str());

  py::class_<RunOptions> run_options(m, "RunOptions", "When a run ends, and what it records");
  bind_run_fields(run_options);
  const std::string run_init =
      "The defaults, with the options given as keywords set (another name raises ValueError, a wrong type "
      "TypeError):\n" +
      keyword_lines(py::cast(RunOptions{}), kRunFields);
  run_options.def(py::init(&from_keywords<RunOptions>), run_init.c_str());
  std::vector<std::string> run_fields;
  for (const auto& field : kRunFields) run_fields.push_back(field.first);
  python::def_value_semantics(run_options, run_fields, "RunOptions");
  python::add_python_names(droplet_fields);
  python::add_python_names(run_fields);
  python::add_python_names({"r_min", "r_max", "pixel_size", "trace_interval", "check_interval"});

  python::bind_medium(m);

  bind_stores(m);
  python::translate_library_errors();  // after bind_stores: its StoreError
  m.def("_columns", [] {
    py::dict d;
    py::list names, units, meanings;
    for (const cli::ColumnName& c : cli::column_names())
      names.append(c.name), units.append(c.unit), meanings.append(c.meaning);
    d["name"] = names, d["unit"] = units, d["meaning"] = meanings;
    return d;
  });
  bind_commands(m);
  bind_held_out(m);
  softdrop::python::bind_two_droplets(m);
  python::bind_tortuosity(m);

  m.def(
      "_simulate",
      [](const Medium& medium, double x0, const DropletParams& params, const RunOptions& run, bool path,
         int trace_interval) {
        check(params, run);
        if (!(x0 >= 0 && x0 <= medium.width))
          throw std::invalid_argument("x0 = " + std::string(py::repr(py::float_(x0))) + ": must be in [0, width]");
        if (trace_interval < 0)
          throw std::invalid_argument("trace_interval = " + std::to_string(trace_interval) + ": must be >= 1");
        RunOptions options = run;
        if (path && options.path_interval == 0) options.path_interval = 100;
        bool interrupted = false;
        RunSummary s;
        AreaTrace trace;
        {
          py::gil_scoped_release release;
          try {
            if (trace_interval > 0) {  // as `softdrop simulate --trace`: the run, then its replay recording the area
              trace = trace_area(params, medium, x0, interruptible(options, &interrupted), trace_interval);
              s = trace.run;
            } else {
              s = Simulation(params, medium).run(x0, interruptible(options, &interrupted));
            }
          } catch (const RunCancelled&) {
          }
        }
        if (interrupted) throw py::error_already_set();
        py::dict d = summary_dict(s, path);
        if (trace_interval > 0) {
          py::array_t<double> rows({static_cast<py::ssize_t>(trace.t.size()), py::ssize_t{3}});
          auto v = rows.mutable_unchecked<2>();
          for (std::size_t i = 0; i < trace.t.size(); ++i) {
            const auto k = static_cast<py::ssize_t>(i);
            v(k, 0) = trace.t[i], v(k, 1) = trace.area[i], v(k, 2) = trace.area[i] / trace.s0;  // NaN: never entered
          }
          d["trace"] = rows;
          d["enter"] = trace.enter, d["leave"] = trace.leave, d["s0"] = trace.s0;
          d["inside_min_area_ratio"] = trace.min_ratio, d["inside_max_area_ratio"] = trace.max_ratio;
        }
        return d;
      },
      py::arg("medium"), py::arg("x0"), py::arg("params"), py::arg("run"), py::arg("path"), py::arg("trace_interval"));

  m.def(
      "_simulate_many",
      [](const Medium& medium, int droplets, std::uint64_t seed, int threads, const DropletParams& params,
         const RunOptions& run) {
        check(params, run);
        if (droplets < 1 || droplets > 10'000'000)
          throw std::invalid_argument("n = " + std::to_string(droplets) + ": must be in [1, 1e7]");
        cli::check_threads(threads);  // the program's rule and message
        BatchOptions batch;
        batch.droplets = droplets, batch.seed = seed, batch.threads = threads;
        const auto progress = stop_on_ctrl_c();
        std::vector<RunSummary> runs;
        {
          py::gil_scoped_release release;
          runs = run_batch(params, medium, run, batch, progress);
        }
        py::list out;
        for (const RunSummary& s : runs) out.append(summary_dict(s, false));
        return out;
      },
      py::arg("medium"), py::arg("n"), py::arg("seed"), py::arg("threads"), py::arg("params"), py::arg("run"));

  m.def(
      "_rigid_descents",
      [](const Medium& medium, double radius, const std::vector<double>& x0s, bool paths) {
        std::vector<RigidDescent> runs;
        {
          py::gil_scoped_release release;
          runs = rigid_descents(medium, radius, x0s, paths);
        }
        py::dict columns;  // one entry a column, one element a start
        const auto column = [&](auto field) {
          std::vector<std::decay_t<decltype(runs.front().*field)>> values;
          for (const RigidDescent& r : runs) values.push_back(r.*field);
          return values;
        };
        columns["start_x"] = x0s;
        columns["passed"] = column(&RigidDescent::passed);
        columns["tortuosity"] = column(&RigidDescent::tortuosity);
        columns["x"] = column(&RigidDescent::x);
        columns["y"] = column(&RigidDescent::y);
        columns["slides"] = column(&RigidDescent::slides);
        if (!paths) return columns;
        py::list rows_of;  // each start's path: rows of x, y
        for (const RigidDescent& r : runs) rows_of.append(python::xy_array(r.path_x, r.path_y));
        columns["path"] = rows_of;
        return columns;
      },
      py::arg("medium"), py::arg("radius"), py::arg("x0s"), py::arg("paths"));
}
