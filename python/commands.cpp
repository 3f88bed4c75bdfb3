// The program's optimize and sweep commands run in this process, parsed and run by the command
// line's own code: the same options, defaults, checks, messages and files as `softdrop optimize`
// and `softdrop sweep`. The command runs with the GIL released; after each committed generation or
// medium it takes the GIL to look for Ctrl-C and to call the Python callback.
#include <pybind11/stl.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "bindings.hpp"
#include "cli/cli.hpp"

namespace softdrop::python {
namespace {

// JSON to Python objects (the summaries and progress events are small).
py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

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

// A value the option cannot take, said as a Python keyword's wrong type: CLI11's "Could not convert:
// --generations = 2.5" is "generations: a whole number, not 2.5".
std::string conversion_line(const cli::Cli& cli, const std::string& command, const std::string& what) {
  const std::size_t dashes = what.find("--"), equals = what.find(" = ");
  if (dashes == std::string::npos || equals == std::string::npos || equals < dashes) return python_words(what);
  const std::string option = what.substr(dashes, equals - dashes);
  const std::string value = what.substr(equals + 3);
  const CLI::App* sub = cli.app.get_subcommand(command);  // optimize or sweep: run_command checked
  const CLI::Option* o = sub ? sub->get_option_no_throw(option) : nullptr;
  const std::string type = o ? o->get_type_name() : "";
  const char* wanted = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0 ? "a whole number"
                       : type.rfind("FLOAT", 0) == 0                           ? "a number"
                                                                               : "a value it takes";
  std::string name = python_words(option);
  if (name == "lambda") name = "lambda_";  // the keyword, as `lambda` is Python's
  return name + ": " + wanted + ", not " + value;
}

py::object run_command(const std::vector<std::string>& args, const py::object& callback) {
  if (args.size() < 2 || (args[1] != "optimize" && args[1] != "sweep"))
    throw std::invalid_argument("command: must be optimize or sweep");
  if (!callback.is_none() && !PyCallable_Check(callback.ptr()))
    throw std::invalid_argument("callback: must be callable (or None)");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  const int argc = static_cast<int>(argv.size());

  cli::Cli cli;
  try {
    cli.parse(argc, argv.data());
  } catch (const CLI::ConversionError& e) {
    throw py::type_error(conversion_line(cli, args[1], e.what()));
  } catch (const CLI::ExtrasError& e) {  // an option the command does not have: Python's own words for it
    const CLI::App* sub = cli.app.get_subcommand(args[1]);
    for (std::size_t i = 2; i < args.size(); ++i)
      if (args[i].rfind("--", 0) == 0 && sub->get_option_no_throw(args[i]) == nullptr) {
        const std::string line = cli.parse_error_line(e, argc, argv.data());
        const std::size_t mean = line.find(" (did you mean");
        throw py::type_error(args[1] + "() got an unexpected keyword argument '" + python_words(args[i]) + "'" +
                             (mean == std::string::npos ? "" : python_words(line.substr(mean))));
      }
    throw std::invalid_argument(cli.parse_error_line(e, argc, argv.data()));
  } catch (const CLI::ParseError& e) {
    throw std::invalid_argument(cli.parse_error_line(e, argc, argv.data()));
  }
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
      const py::object answer = callback(to_python(event));
      return answer.is_none() || PyObject_IsTrue(answer.ptr()) != 0;
    } catch (py::error_already_set& e) {
      e.restore();
      error.fetch();
      return false;
    }
  };
  cli.set_host(&host);
  {
    py::gil_scoped_release release;
    cli.run();
  }
  if (error.pending()) error.raise();
  return to_python(host.summary);
}

}  // namespace

void bind_commands(py::module_& m) {
  // Their options are the functions' keywords, '-' spelled '_': so are they in messages.
  const cli::Cli cli;
  std::vector<std::string> keywords;
  const std::function<void(const CLI::App*)> collect = [&](const CLI::App* app) {
    for (const CLI::Option* o : app->get_options())
      for (std::string name : o->get_lnames()) {
        for (char& c : name)
          if (c == '-') c = '_';
        keywords.push_back(name);
      }
    for (const CLI::App* group : app->get_subcommands([](const CLI::App*) { return true; })) collect(group);
  };
  for (const char* command : {"optimize", "sweep"}) collect(cli.app.get_subcommand(command));
  add_python_names(keywords);

  m.def("_run_command", &run_command, py::arg("args"), py::arg("callback"),
        "Runs `softdrop optimize` or `softdrop sweep` with these arguments (args[0] is the program name) "
        "in this process; returns the command's JSON summary");
}

}  // namespace softdrop::python
