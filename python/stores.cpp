// Search histories and sweep stores read into columns (a dict of equal-length lists per table,
// which pandas takes as a DataFrame), through the store interfaces the program reads them with.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "bindings.hpp"
#include "cli/columns.hpp"
#include "cli/sweep_report_command.hpp"
#include "service/sweep_droplet.hpp"
#include "softdrop/store.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop::python {
namespace {

PyObject* g_store_error = nullptr;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A table built column by column: add a row's cells by name, in the same order every row.
class Columns {
 public:
  explicit Columns(std::vector<std::string> names) : names_(std::move(names)) {
    cli::check_column_names(names_);
    for (const std::string& n : names_) columns_[n] = py::list();
  }
  py::list& operator[](const std::string& name) { return columns_.at(name); }
  py::dict dict() const {
    py::dict d;
    for (const std::string& n : names_) d[n.c_str()] = columns_.at(n);
    return d;
  }

 private:
  std::vector<std::string> names_;
  std::map<std::string, py::list> columns_;
};

py::object or_none(bool present, py::object value) { return present ? value : py::none(); }

// Anything the store throws while reading is the store's: StoreError, its message naming the file.
template <class Read>
auto in_store(Read&& read) {
  try {
    return read();
  } catch (const std::runtime_error& e) {
    PyErr_SetString(g_store_error, python_words(e.what()).c_str());
    throw py::error_already_set();
  }
}

py::dict history_tables(History& h, bool arrangements) {
  // The columns of the database's views (runs_view, ...), in their order.
  Columns runs({"run",         "created",  "updated",         "version",         "status", "strategy",    "objective",
                "seed",        "lambda",   "grains",          "width",           "height", "periodic",    "generations",
                "evaluations", "droplets", "best_tortuosity", "best_generation", "island", "archipelago", "params"});
  Columns gens({"run", "generation", "kind", "accepted_candidate", "best_tortuosity", "touched", "seconds", "finished",
                "state", "parent_tortuosity", "parent_passed"});
  Columns cands({"run", "generation", "candidate", "kind", "moved_grain", "moved", "outcome", "reason", "tortuosity",
                 "steps", "touched", "seconds", "droplets", "passed"});
  Columns grains({"run", "generation", "grain", "x", "y", "r", "touched"});
  Columns paths({"run", "generation", "point", "x", "y"});
  Columns held({"run",
                "generation",
                "seed",
                "starts",
                "created",
                "version",
                "dt",
                "passed",
                "mean_tortuosity",
                "standard_error",
                "q1",
                "median",
                "q3",
                "half_dt",
                "half_dt_passed",
                "half_dt_mean_tortuosity",
                "half_dt_standard_error",
                "paired",
                "dt_shift",
                "dt_shift_error"});
  // history --best's rows, with the run.
  Columns best({"run", "generation", "kind", "best_tortuosity", "touched", "held_out_tortuosity",
                "held_out_standard_error", "held_out_starts", "re_runs"});
  for (const RunRecord& r : h.runs()) {
    const std::vector<ValidationRecord> validations = h.validations(r.id);
    const std::vector<GenerationRecord> generations = h.generations(r.id);
    for (const ValidationRecord& v : validations) {
      held["run"].append(r.id), held["generation"].append(v.generation), held["seed"].append(v.seed);
      held["starts"].append(v.starts), held["created"].append(v.created), held["version"].append(v.version);
      held["dt"].append(v.dt), held["passed"].append(v.passed), held["mean_tortuosity"].append(v.mean_t);
      held["standard_error"].append(v.standard_error), held["q1"].append(v.q1), held["median"].append(v.median);
      held["q3"].append(v.q3), held["half_dt"].append(v.half_dt);
      held["half_dt_passed"].append(or_none(v.half_dt, py::int_(v.half_dt_passed)));
      held["half_dt_mean_tortuosity"].append(v.half_dt ? v.half_dt_mean_t : kNaN);
      held["half_dt_standard_error"].append(v.half_dt ? v.half_dt_standard_error : kNaN);
      held["paired"].append(or_none(v.half_dt, py::int_(v.paired)));
      held["dt_shift"].append(v.half_dt ? v.dt_shift : kNaN);
      held["dt_shift_error"].append(v.half_dt ? v.dt_shift_error : kNaN);
    }
    const auto params = nlohmann::json::parse(r.params, nullptr, false);
    const auto param = [&](const char* key, const char* otherwise) {
      return params.is_object() && params.contains(key) && params[key].is_string() ? params[key].get<std::string>()
                                                                                   : std::string(otherwise);
    };
    runs["run"].append(r.id), runs["created"].append(r.created), runs["updated"].append(r.updated);
    runs["version"].append(r.version), runs["status"].append(r.status);
    runs["strategy"].append(param("strategy", "paper")), runs["objective"].append(param("objective", "single"));
    runs["seed"].append(r.seed);
    runs["lambda"].append(r.lambda), runs["grains"].append(r.grains), runs["width"].append(r.width);
    runs["height"].append(r.height), runs["periodic"].append(r.periodic), runs["generations"].append(r.generations);
    runs["evaluations"].append(r.evaluations), runs["droplets"].append(r.droplets),
        runs["best_tortuosity"].append(r.best_t);
    runs["best_generation"].append(r.best_generation), runs["params"].append(r.params);
    runs["island"].append(or_none(r.island >= 0, py::int_(r.island)));
    runs["archipelago"].append(or_none(r.archipelago > 0, py::int_(r.archipelago)));
    // Parameters that are not a JSON object: read_history raises StoreError naming the file.
    const BestCurve curve = params.is_object() ? best_rows(r, generations, validations) : BestCurve{};
    for (const BestRow& b : curve.rows) {
      const std::optional<ValidationRecord>& v = b.held_out;
      best["run"].append(r.id), best["generation"].append(b.point.generation), best["kind"].append(b.kind);
      best["best_tortuosity"].append(b.point.value), best["touched"].append(b.touched);
      best["held_out_tortuosity"].append(v ? v->mean_t : kNaN);
      best["held_out_standard_error"].append(v ? v->standard_error : kNaN);
      best["held_out_starts"].append(or_none(v.has_value(), py::int_(v ? v->starts : 0)));
      best["re_runs"].append(or_none(curve.robust, py::int_(b.point.re_runs)));
    }
    for (const GenerationRecord& g : generations) {
      gens["run"].append(r.id), gens["generation"].append(g.generation), gens["kind"].append(g.kind);
      gens["accepted_candidate"].append(or_none(g.accepted >= 0, py::int_(g.accepted)));
      gens["best_tortuosity"].append(g.best_t), gens["touched"].append(g.touched), gens["seconds"].append(g.seconds);
      gens["finished"].append(g.finished), gens["state"].append(g.state);
      const bool rerun = g.parent_passed > 0 || !std::isnan(g.parent_t);
      gens["parent_tortuosity"].append(g.parent_t);
      gens["parent_passed"].append(or_none(rerun, py::int_(g.parent_passed)));
      for (const CandidateRecord& c : g.candidates) {
        cands["run"].append(r.id), cands["generation"].append(g.generation), cands["candidate"].append(c.index);
        cands["kind"].append(c.kind.empty() ? py::object(py::none()) : py::object(py::str(c.kind)));
        cands["moved_grain"].append(or_none(c.moved_grain >= 0, py::int_(c.moved_grain)));
        cands["moved"].append(c.moved), cands["outcome"].append(c.outcome), cands["reason"].append(c.reason);
        cands["tortuosity"].append(c.outcome == "passed" ? c.tortuosity : kNaN);
        cands["steps"].append(c.steps), cands["touched"].append(c.touched), cands["seconds"].append(c.seconds);
        cands["droplets"].append(c.droplets), cands["passed"].append(c.passed);
      }
      // The stored arrangements: generation 0's and each one a generation kept.
      if (!arrangements || (g.generation != 0 && g.accepted < 0)) continue;
      const Configuration c = h.configuration(r.id, g.generation);
      std::vector<bool> touched(c.medium.grains.size(), false);
      for (const std::int32_t i : c.eval.touched) touched.at(static_cast<std::size_t>(i)) = true;
      for (std::size_t i = 0; i < c.medium.grains.size(); ++i) {
        const Grain& gr = c.medium.grains[i];
        grains["run"].append(r.id), grains["generation"].append(g.generation), grains["grain"].append(i);
        grains["x"].append(gr.x), grains["y"].append(gr.y), grains["r"].append(gr.r);
        grains["touched"].append(static_cast<bool>(touched[i]));
      }
      for (std::size_t i = 0; i < c.eval.path_x.size(); ++i) {
        paths["run"].append(r.id), paths["generation"].append(g.generation), paths["point"].append(i);
        paths["x"].append(c.eval.path_x[i]), paths["y"].append(c.eval.path_y[i]);
      }
    }
  }
  py::dict out;
  out["runs"] = runs.dict(), out["generations"] = gens.dict(), out["candidates"] = cands.dict();
  out["grains"] = grains.dict(), out["paths"] = paths.dict(), out["validations"] = held.dict();
  out["best"] = best.dict();
  return out;
}

py::dict sweep_tables(SweepStore& store, std::int64_t only) {
  Columns sweeps({"sweep", "created", "updated", "version", "status", "params", "units", "done"});
  Columns media({"sweep", "porosity_index", "medium_index", "target_porosity", "porosity", "grains", "medium_seed",
                 "droplets", "passed", "stuck", "timeout", "diverged", "mean_tortuosity", "standard_error",
                 "stuck_fraction", "seconds"});
  Columns droplets({"sweep", "porosity_index", "medium_index", "droplet", "start_x", "outcome", "tortuosity", "steps",
                    "shaken_at", "route_tortuosity"});
  Columns seconds({"sweep", "porosity_index", "medium_index", "droplet", "start_x", "outcome", "tortuosity", "steps",
                   "shaken_at", "route_tortuosity", "released_at", "first_held_at", "held_at", "contact_steps",
                   "shared_touched"});
  Columns points({"sweep", "target_porosity", "porosity", "media", "droplets", "passed", "mean_tortuosity",
                  "standard_error", "media_passed", "media_standard_error", "stuck_fraction", "per_medium_tortuosity",
                  "per_medium_standard_error"});
  const std::vector<SweepRecord> all = only > 0 ? std::vector<SweepRecord>{store.sweep(only)} : store.sweeps();
  for (const SweepRecord& s : all) {
    sweeps["sweep"].append(s.id), sweeps["created"].append(s.created), sweeps["updated"].append(s.updated);
    sweeps["version"].append(s.version), sweeps["status"].append(s.status), sweeps["params"].append(s.params);
    sweeps["units"].append(s.units), sweeps["done"].append(s.done);
    const std::vector<SweepMedium> stored = store.media(s.id);
    for (const SweepMedium& m : stored) {
      media["sweep"].append(s.id), media["porosity_index"].append(m.unit.porosity);
      media["medium_index"].append(m.unit.medium), media["target_porosity"].append(m.target_porosity);
      media["porosity"].append(m.porosity), media["grains"].append(m.grains),
          media["medium_seed"].append(m.medium_seed);
      media["droplets"].append(m.droplets.size()), media["passed"].append(m.passed), media["stuck"].append(m.stuck);
      media["timeout"].append(m.timeout), media["diverged"].append(m.diverged);
      media["mean_tortuosity"].append(m.passed ? m.mean_t : kNaN);
      media["standard_error"].append(m.passed > 1 ? m.standard_error : kNaN);
      media["stuck_fraction"].append(m.stuck_fraction), media["seconds"].append(m.seconds);
      // One droplet's row of `table` (droplets, or second_droplets' first columns).
      const auto add_droplet = [&](Columns& table, const SweepDroplet& d) {
        table["sweep"].append(s.id), table["porosity_index"].append(m.unit.porosity);
        table["medium_index"].append(m.unit.medium), table["droplet"].append(d.droplet);
        table["start_x"].append(d.start_x), table["outcome"].append(to_string(d.outcome));
        table["tortuosity"].append(d.outcome == Outcome::passed ? d.tortuosity : kNaN);
        table["steps"].append(d.steps);
        table["shaken_at"].append(d.shaken_at), table["route_tortuosity"].append(d.route_tortuosity);
      };
      for (const SweepDroplet& d : m.droplets) add_droplet(droplets, d);
      for (const SweepSecond& p : m.second_droplets) {
        add_droplet(seconds, p.run);
        seconds["released_at"].append(p.released_at), seconds["first_held_at"].append(p.first_held_at);
        seconds["held_at"].append(p.held_at), seconds["contact_steps"].append(p.contact_steps);
        seconds["shared_touched"].append(p.shared_touched);
      }
    }
    for (const SweepPoint& p : sweep_points(stored)) {  // as `softdrop sweep-report` aggregates them
      points["sweep"].append(s.id), points["target_porosity"].append(p.target_porosity);
      points["porosity"].append(p.porosity);
      points["media"].append(p.media), points["droplets"].append(p.droplets), points["passed"].append(p.passed);
      points["mean_tortuosity"].append(p.passed ? p.mean_t : kNaN);
      points["standard_error"].append(p.passed > 1 ? p.standard_error : kNaN);
      points["media_passed"].append(p.media_passed);
      points["media_standard_error"].append(p.media_passed > 1 ? p.media_standard_error : kNaN);
      points["stuck_fraction"].append(p.stuck_fraction);
      points["per_medium_tortuosity"].append(p.media_passed ? p.per_medium_t : kNaN);
      points["per_medium_standard_error"].append(p.media_passed > 1 ? p.per_medium_standard_error : kNaN);
    }
  }
  py::dict out;
  out["sweeps"] = sweeps.dict(), out["media"] = media.dict(), out["droplets"] = droplets.dict();
  out["second_droplets"] = seconds.dict(), out["points"] = points.dict();
  return out;
}

// One droplet of a sweep as the sweep ran it (service/sweep_droplet.hpp), for simulate.
py::dict sweep_droplet(SweepStore& store, const std::string& db, std::int64_t sweep, int porosity_index,
                       int medium_index, int droplet) {
  const StoredSweepDroplet s =
      stored_sweep_droplet(store, db, cli::pick_sweep(store, sweep, db), porosity_index, medium_index, droplet);
  py::dict out;
  out["medium"] = generate_medium(s.medium);
  out["params"] = s.options.droplet;
  out["run"] = s.options.run;
  out["x0"] = s.droplet.start_x;
  out["outcome"] = to_string(s.droplet.outcome);
  out["tortuosity"] = s.droplet.outcome == Outcome::passed ? s.droplet.tortuosity : kNaN;
  out["steps"] = s.droplet.steps;
  out["target_porosity"] = s.medium.porosity;
  out["porosity"] = s.porosity;
  out["medium_seed"] = s.medium.seed;
  out["sweep"] = s.sweep;
  return out;
}

}  // namespace

py::array_t<double> xy_array(const std::vector<double>& x, const std::vector<double>& y) {
  py::array_t<double> a({static_cast<py::ssize_t>(x.size()), py::ssize_t{2}});
  auto v = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < x.size(); ++i)
    v(static_cast<py::ssize_t>(i), 0) = x[i], v(static_cast<py::ssize_t>(i), 1) = y[i];
  return a;
}

PyObject* store_error() { return g_store_error; }

void bind_stores(py::module_& m) {
  // A file the store refuses (missing, foreign, damaged), wherever it is opened: the store's one
  // line, naming the file.
  static py::exception<DatabaseError> error =
      py::register_exception<DatabaseError>(m, "StoreError", PyExc_RuntimeError);
  g_store_error = error.ptr();
  error.attr("__doc__") =
      "A database softdrop cannot use (missing, not softdrop's, damaged, or written by a newer softdrop): the "
      "message names the file and what is wrong with it. A RuntimeError.";

  m.def(
      "_read_history",
      [](const std::string& db, bool arrangements) {
        return in_store([&] {
          auto h = open_history(db, OpenMode::read_only);
          return history_tables(*h, arrangements);
        });
      },
      py::arg("db"), py::arg("arrangements"));
  m.def(
      "_read_sweep",
      [](const std::string& db, std::int64_t sweep) {
        return in_store([&] {
          auto store = open_sweep_store(db, OpenMode::read_only);
          return sweep_tables(*store, sweep);
        });
      },
      py::arg("db"), py::arg("sweep"));
  m.def(
      "_sweep_droplet",
      [](const std::string& db, std::int64_t sweep, int porosity_index, int medium_index, int droplet) {
        return in_store([&] {
          auto store = open_sweep_store(db, OpenMode::read_only);
          return sweep_droplet(*store, db, sweep, porosity_index, medium_index, droplet);
        });
      },
      py::arg("db"), py::arg("sweep"), py::arg("porosity_index"), py::arg("medium_index"), py::arg("droplet"));
  m.def(
      "_arrangement",
      [](const std::string& db, std::int64_t run, std::int64_t generation) {
        return in_store([&] {
          auto h = open_history(db, OpenMode::read_only);
          const Configuration c = h->configuration(run, generation);
          py::dict d;
          d["medium"] = c.medium;
          d["generation"] = c.generation;
          d["tortuosity"] = c.eval.tortuosity;
          // Its values as history --best gives them: in the search and held out.
          const ArrangementValues v = arrangement_values(*h, run, c);
          d["objective"] = v.objective;
          d["best_tortuosity"] = v.in_search;
          d["re_runs"] = v.re_runs;
          const bool held = v.held_out.has_value();
          d["held_out_tortuosity"] = held ? py::cast(v.held_out->mean_t) : py::none();
          d["held_out_standard_error"] = held ? py::cast(v.held_out->standard_error) : py::none();
          d["held_out_starts"] = held ? py::cast(v.held_out->starts) : py::none();
          d["touched"] = c.eval.touched.size();
          d["touched_grains"] = c.eval.touched;
          d["path"] = xy_array(c.eval.path_x, c.eval.path_y);
          return d;
        });
      },
      py::arg("db"), py::arg("run"), py::arg("generation"));
}

}  // namespace softdrop::python
