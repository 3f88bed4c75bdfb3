// optimize and sweep: the library's run of a search or a sweep (softdrop/service.hpp), built from
// keywords read as its named values (service/run_values.hpp), with the program's defaults, presets,
// checks, progress lines and summary. The run goes on with the GIL released; after each committed
// generation or medium it takes the GIL to look for Ctrl-C and to call the Python callback.
#include <pybind11/stl.h>

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "arguments.hpp"
#include "bindings.hpp"
#include "cli/cli.hpp"
#include "cli/config_file.hpp"
#include "cli/file_roles.hpp"
#include "cli/output.hpp"
#include "cli/search_setup.hpp"
#include "cli/sweep_command.hpp"
#include "keyword_values.hpp"
#include "service/run_values.hpp"
#include "softdrop/service.hpp"

namespace softdrop::python {
namespace {

// A Python error raised inside the command (the callback's exception, KeyboardInterrupt), held
// while the command winds down and raised again once it has returned.
class PendingError {
 public:
  void fetch() { PyErr_Fetch(&type_, &value_, &traceback_); }
  bool pending() const { return type_ != nullptr; }
  [[noreturn]] void raise() {
    PyErr_Restore(type_, value_, traceback_);
    type_ = value_ = traceback_ = nullptr;
    throw py::error_already_set();
  }
  ~PendingError() {  // with the GIL held: raise() was not reached because the command threw
    Py_XDECREF(type_), Py_XDECREF(value_), Py_XDECREF(traceback_);
  }

 private:
  PyObject *type_ = nullptr, *value_ = nullptr, *traceback_ = nullptr;
};

// Runs `run` (the program's run of a search or a sweep, with a host) with the GIL released, the
// host's events going to `callback`; raises the callback's exception or KeyboardInterrupt once
// the run has returned.
py::object run_hosted(const py::object& callback, const std::function<void(cli::Host*)>& run) {
  if (!callback.is_none() && !PyCallable_Check(callback.ptr()))
    throw std::invalid_argument("callback: must be callable (or None)");
  PendingError error;
  cli::Host host;
  host.on_progress = [&](const nlohmann::json& event) {
    py::gil_scoped_acquire gil;
    // Once the callback has raised (or Ctrl-C came), the media still in flight are committed
    // without calling it again; the first error is the one raised.
    if (error.pending()) return false;
    if (PyErr_CheckSignals() != 0) {  // Ctrl-C: stop here; KeyboardInterrupt once the command is done
      error.fetch();
      return false;
    }
    if (callback.is_none()) return true;
    try {
      const py::object answer = callback(json_to_python(event));
      return answer.is_none() || PyObject_IsTrue(answer.ptr()) != 0;
    } catch (py::error_already_set& e) {
      e.restore();
      error.fetch();
      return false;
    }
  };
  {
    py::gil_scoped_release release;
    run(&host);
  }
  if (error.pending()) error.raise();
  return json_to_python(host.summary);
}

// The options of optimize that are not stored with its run.
std::map<std::string, CallOption> search_call_options(SearchRun* run, cli::SearchOutput* out, std::string* preset) {
  return {
      {"resume",
       [run](py::handle v, const char* k) {
         run->resume = whole_arg(v, k);
         if (run->resume < 1)
           throw py::value_error(std::string(k) + " = " + std::to_string(run->resume) +
                                 ": run ids are whole numbers from 1");
       }},
      {"generations", [run](py::handle v, const char* k) { run->generations = whole_arg(v, k); }},
      {"time-limit", [run](py::handle v, const char* k) { run->time_limit = real_arg(v, k); }},
      {"threads", [run](py::handle v, const char* k) { run->threads = int_arg(v, k); }},
      {"lanes", [run](py::handle v, const char* k) { run->lanes = int_arg(v, k); }},
      {"no-speculation", [run](py::handle v, const char* k) { run->speculate = !bool_arg(v, k); }},
      {"validate-starts", [run](py::handle v, const char* k) { run->validate_starts = int_arg(v, k); }},
      {"start-attempts", [run](py::handle v, const char* k) { run->start.attempts = int_arg(v, k); }},
      {"preset", [preset](py::handle v, const char* k) { *preset = text_arg(v, k); }},
      {"quiet", [out](py::handle v, const char* k) { out->quiet = bool_arg(v, k); }},
      {"verbose", [out](py::handle v, const char* k) { out->verbose = bool_arg(v, k); }},
      {"json", [out](py::handle v, const char* k) { out->json_file = path_arg(v, k).string(); }},
      {"format", [out](py::handle v, const char* k) { out->format = text_arg(v, k); }},
  };
}

// What the program's config files may give a command beside its own options: the keys that shape a
// generated medium, which a command that does not take them leaves alone (the program's own rule).
bool shapes_a_medium(const std::string& key) {
  static const cli::Cli program;
  return cli::shapes_a_medium(program.app, key);
}

py::object optimize(const py::object& db, const py::dict& keywords, const py::object& callback) {
  SearchRun run = default_search_run();
  cli::SearchOutput out;
  std::string preset;
  run.db = out.db = path_arg(db, "db").string();
  nlohmann::json values = search_run_values(run);
  std::vector<std::string> given =
      read_keywords("optimize", keywords, &values, search_call_options(&run, &out, &preset), shapes_a_medium);
  set_search_run_values(values, &run);
  if (!run.start.file.empty())  // (a config file may name the grains its droplet was calibrated among)
    for (const std::string& key : search_medium_keys())
      if (const std::string k = keyword_of(key); keywords.contains(k) && !keywords[k.c_str()].is_none())
        throw std::invalid_argument(key +
                                    ": has no effect with --medium (the grain file fixes the medium); leave it out");
  for (const std::string& key : apply_search_preset(preset, given, &run.search)) given.push_back(key);
  run.given = given;
  if (out.format != "table" && out.format != "json")
    throw std::invalid_argument("format = '" + out.format + "': must be table or json");
  if (std::string why; !run.IsValid(&why)) throw std::invalid_argument(why);
  if (!out.json_file.empty()) {
    cli::check_output_path("--json", out.json_file);
    cli::check_distinct_files({{"--db", run.db, true, true}, {"--json", out.json_file, true, false}});
  }
  return run_hosted(callback, [&](cli::Host* host) { cli::run_search_run(run, out, host, nullptr); });
}

py::object sweep(const py::object& db, const py::dict& keywords, const py::object& callback) {
  SweepRun run;
  run.db = path_arg(db, "db").string();
  std::string preset, shard = "0/1", format = "table";
  bool quiet = false;
  const std::map<std::string, CallOption> options{
      {"threads", [&](py::handle v, const char* k) { run.threads = int_arg(v, k); }},
      {"shard", [&](py::handle v, const char* k) { shard = text_arg(v, k); }},
      {"preset", [&](py::handle v, const char* k) { preset = text_arg(v, k); }},
      {"quiet", [&](py::handle v, const char* k) { quiet = bool_arg(v, k); }},
      {"format", [&](py::handle v, const char* k) { format = text_arg(v, k); }},
  };
  nlohmann::json values = sweep_values(default_sweep());
  const std::vector<std::string> given = read_keywords("sweep", keywords, &values, options, shapes_a_medium);
  run.sweep = sweep_of_values(values, given);
  apply_sweep_preset(preset, given, &run.sweep);
  std::tie(run.shard, run.shards) = cli::parse_shard(shard);
  if (format != "table" && format != "csv" && format != "json")
    throw std::invalid_argument("format = '" + format + "': must be table, csv or json");
  if (std::string why; !run.IsValid(&why)) throw std::invalid_argument(why);
  return run_hosted(callback, [&](cli::Host* host) { cli::run_sweep_run(run, quiet, format, host); });
}

}  // namespace

void bind_commands(py::module_& m) {
  // Their options are the functions' keywords, '-' spelled '_': so are they in messages.
  SearchRun run;
  cli::SearchOutput out;
  std::string preset;
  add_python_names(keyword_names(search_run_values(run), search_call_options(&run, &out, &preset)));
  add_python_names(keyword_names(sweep_values(default_sweep()), {}));
  add_python_names({"shard"});

  m.def("_optimize", &optimize, py::arg("db"), py::arg("keywords"), py::arg("callback"),
        "Runs a search as `softdrop optimize` does, on the history `db`, with these keywords (the program's long "
        "options, '-' spelled '_'); returns its JSON summary");
  m.def("_sweep", &sweep, py::arg("db"), py::arg("keywords"), py::arg("callback"),
        "Runs a sweep as `softdrop sweep` does, on the store `db`, with these keywords; returns its summary");
}

}  // namespace softdrop::python
