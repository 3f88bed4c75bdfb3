#pragma once
// Python arguments read as the library's types, and the library's errors said in Python's words.
//
// A wrong type raises TypeError and a value out of range ValueError, each naming the Python
// argument ("porosity: a number, not '0.8'"). pybind11's own conversion would instead raise its
// "incompatible function arguments" dump listing every overload, and would cut 2.5 to 2 where an
// int is wanted.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

namespace softdrop::python {

namespace py = pybind11;

/// A real number: a Python or numpy int or float, not a bool, a str or None.
double real_arg(py::handle value, const char* name);
/// A whole number (anything with __index__: int, numpy's integers), not 2.5 or 2.0.
long long whole_arg(py::handle value, const char* name);
/// A whole number that fits an int (ValueError beyond it).
int int_arg(py::handle value, const char* name);
/// A random seed: a whole number from 0 to 2^64 - 1.
std::uint64_t seed_arg(py::handle value, const char* name);
/// A number of type T (bool, an integer type or a floating type) by the rules above.
template <class T>
T number_arg(py::handle value, const char* name);
/// True or False (numpy's bools too; 0 and 1 as well).
bool bool_arg(py::handle value, const char* name);
/// A str.
std::string text_arg(py::handle value, const char* name);
/// A file name: a str or os.PathLike (not bytes).
std::filesystem::path path_arg(py::handle value, const char* name);
/// A sequence (or 1D array) of real numbers.
std::vector<double> reals_arg(py::handle value, const char* name);

template <class T>
T number_arg(py::handle value, const char* name) {
  if constexpr (std::is_same_v<T, bool>)
    return bool_arg(value, name);
  else if constexpr (std::is_same_v<T, int>)
    return int_arg(value, name);
  else if constexpr (std::is_integral_v<T>)
    return static_cast<T>(whole_arg(value, name));
  else
    return static_cast<T>(real_arg(value, name));
}

/// The names of the module's keyword arguments and attributes that the library spells with '-'
/// (r_min: r-min), so that its messages can be said with Python's names.
void add_python_names(const std::vector<std::string>& names);
/// A library message in Python's words: an option as the command line spells it ("--db 'x.db'",
/// "r-max = 3: must be >= r-min") becomes the Python argument ("db 'x.db'", "r_max = 3: must be >=
/// r_min"). Free text ("non-overlapping") stays as it is.
std::string python_words(const std::string& message);
/// Has the library's errors raised in Python's words: std::invalid_argument as ValueError, and
/// the store's DatabaseError as softdrop.StoreError (bind_stores makes it: call this after).
void translate_library_errors();

}  // namespace softdrop::python
