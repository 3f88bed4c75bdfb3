// softdrop.held_out: the held-out value of a medium, as `softdrop validate` gives it, with every
// droplet as columns for a DataFrame.
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <string>

#include "bindings.hpp"
#include "softdrop/batch.hpp"

namespace softdrop::python {
namespace {

py::object number(double v) { return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none()); }

py::dict summary(const HeldOutRuns& r) {
  py::dict d;
  d["dt"] = r.dt, d["starts"] = r.starts, d["passed"] = r.passed, d["stuck"] = r.stuck;
  d["timeout"] = r.timeout, d["diverged"] = r.diverged, d["pass_fraction"] = r.pass_fraction;
  d["mean_tortuosity"] = number(r.mean_t), d["standard_error"] = number(r.standard_error);
  d["q1"] = number(r.q1), d["median"] = number(r.median), d["q3"] = number(r.q3);
  return d;
}

}  // namespace

void bind_held_out(py::module_& m) {
  m.def(
      "_held_out",
      [](const Medium& medium, int starts, std::uint64_t seed, bool half_dt, int threads, const DropletParams& params,
         const RunOptions& run) {
        HeldOutOptions o;
        o.starts = starts, o.seed = seed, o.half_dt = half_dt, o.threads = threads;
        std::string why;
        if (!o.IsValid(&why) || !params.IsValid(&why) || !run.IsValid(&why)) throw std::invalid_argument(why);
        const auto progress = stop_on_ctrl_c();
        HeldOutValue v;
        {
          py::gil_scoped_release release;
          v = held_out_value(params, medium, run, o, progress);
        }
        py::dict out;
        out["at_dt"] = summary(v.at_dt);
        if (half_dt) {
          out["at_half_dt"] = summary(v.at_half_dt);
          out["dt_shift"] = number(v.dt_shift), out["dt_shift_error"] = number(v.dt_shift_error);
          out["paired"] = v.paired;
        }
        py::dict rows;  // one row a droplet and time step
        py::list start, start_x, dt, outcome, tortuosity, steps;
        for (const HeldOutRuns* r : {&v.at_dt, &v.at_half_dt})
          for (std::size_t i = 0; i < r->runs.size(); ++i) {
            const RunSummary& s = r->runs[i];
            start.append(i), start_x.append(s.start_x), dt.append(r->dt), outcome.append(to_string(s.outcome));
            tortuosity.append(s.outcome == Outcome::passed ? s.tortuosity : std::numeric_limits<double>::quiet_NaN());
            steps.append(s.steps);
          }
        rows["start"] = start, rows["start_x"] = start_x, rows["dt"] = dt, rows["outcome"] = outcome;
        rows["tortuosity"] = tortuosity, rows["steps"] = steps;
        out["runs"] = rows;
        return out;
      },
      py::arg("medium"), py::arg("starts"), py::arg("seed"), py::arg("half_dt"), py::arg("threads"), py::arg("params"),
      py::arg("run"));
}

}  // namespace softdrop::python
