#pragma once
// optimize's and sweep's keywords read as the library's named values (service/run_values.hpp):
// each keyword is an option's name spelled with '_' (r_min: "r-min"; lambda_: "lambda"), read as
// the type of that option's default, after the values of a `config` file.
#include <pybind11/pybind11.h>

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace softdrop::python {

namespace py = pybind11;

/// An option of the call that is not a named value of the run (resume, threads, quiet, ...): how a
/// value, read and checked by `set` (which names the keyword in its errors), applies.
using CallOption = std::function<void(py::handle value, const char* keyword)>;

/// Reads `keywords` (and the values of the file named by its `config`, first) into `values`
/// (a keyword of None is left out, as if not given),
/// whose keys are the named values and the type of each the type it takes, or hands them to
/// `options`. Returns the names given (by keyword or config file), for SearchRun::given.
/// A keyword no option has raises TypeError as Python does ("optimize() got an unexpected keyword
/// argument 'x' (did you mean y?)"); a value of the wrong type raises TypeError naming the keyword;
/// a config file's key that no option has raises ValueError naming the file and the key (a key
/// that `shapes_a_medium` says shapes a generated medium is left out, as the program does).
std::vector<std::string> read_keywords(const std::string& command, const py::dict& keywords, nlohmann::json* values,
                                       const std::map<std::string, CallOption>& options,
                                       const std::function<bool(const std::string&)>& shapes_a_medium);

/// JSON as Python objects (dicts, lists, numbers, str; small: summaries, events, config values).
py::object json_to_python(const nlohmann::json& j);
/// The keyword of a library name: '-' as '_', and lambda as lambda_ (`lambda` is Python's).
std::string keyword_of(std::string name);
/// The keywords of the values and options (Python's spelling, '_'), for add_python_names.
std::vector<std::string> keyword_names(const nlohmann::json& values, const std::map<std::string, CallOption>& options);

}  // namespace softdrop::python
