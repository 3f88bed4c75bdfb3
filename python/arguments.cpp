#include "arguments.hpp"

#include <pybind11/numpy.h>

#include <cctype>
#include <limits>
#include <set>
#include <stdexcept>

#include "bindings.hpp"
#include "softdrop/store.hpp"

namespace softdrop::python {
namespace {

using namespace pybind11::literals;

std::string repr_of(py::handle value) { return py::repr(value); }

[[noreturn]] void wrong_type(py::handle value, const char* name, const char* wanted) {
  throw py::type_error(std::string(name) + ": " + wanted + ", not " + repr_of(value));
}

// The hyphenated spellings of the Python names given to add_python_names ("r-min").
std::set<std::string, std::less<>>& hyphenated() {
  static std::set<std::string, std::less<>> names;
  return names;
}

// A whole number as a Python int (through __index__), not a bool: the one check of whole_arg and
// seed_arg.
py::object index_of(py::handle value, const char* name) {
  if (PyBool_Check(value.ptr())) wrong_type(value, name, "a whole number");
  py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) {
    PyErr_Clear();
    wrong_type(value, name, "a whole number");
  }
  return index;
}

bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_'; }

}  // namespace

double real_arg(py::handle value, const char* name) {
  if (PyBool_Check(value.ptr()) || PyUnicode_Check(value.ptr()) || !PyNumber_Check(value.ptr()) ||
      py::isinstance<py::array>(value))
    wrong_type(value, name, "a number");
  const double v = PyFloat_AsDouble(value.ptr());
  if (v == -1.0 && PyErr_Occurred()) {  // a complex number, or an object whose __float__ failed
    PyErr_Clear();
    wrong_type(value, name, "a real number");
  }
  return v;
}

long long whole_arg(py::handle value, const char* name) {
  const py::object index = index_of(value, name);
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0) throw py::value_error(std::string(name) + " = " + repr_of(index) + ": too large");
  return v;
}

int int_arg(py::handle value, const char* name) {
  const long long v = whole_arg(value, name);
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    throw py::value_error(std::string(name) + " = " + std::to_string(v) + ": too large");
  return static_cast<int>(v);
}

std::uint64_t seed_arg(py::handle value, const char* name) {
  const py::object index = index_of(value, name);
  if (index < py::int_(0)) throw py::value_error(std::string(name) + " = " + repr_of(index) + ": must be >= 0");
  const unsigned long long v = PyLong_AsUnsignedLongLong(index.ptr());
  if (PyErr_Occurred()) {
    PyErr_Clear();
    throw py::value_error(std::string(name) + " = " + repr_of(index) + ": must be < 2**64");
  }
  return v;
}

bool bool_arg(py::handle value, const char* name) {
  if (PyBool_Check(value.ptr())) return value.ptr() == Py_True;
  const py::object numpy_bool = py::module_::import("numpy").attr("bool_");
  if (py::isinstance(value, numpy_bool)) return value.cast<bool>();
  if (PyLong_Check(value.ptr())) {
    const long long v = whole_arg(value, name);
    if (v == 0 || v == 1) return v == 1;
  }
  wrong_type(value, name, "True or False");
}

std::string text_arg(py::handle value, const char* name) {
  if (!PyUnicode_Check(value.ptr())) wrong_type(value, name, "a str");
  return value.cast<std::string>();
}

std::filesystem::path path_arg(py::handle value, const char* name) {
  if (PyBytes_Check(value.ptr()) ||
      !(PyUnicode_Check(value.ptr()) || PyObject_HasAttrString(value.ptr(), "__fspath__")))
    wrong_type(value, name, "a file name (str or os.PathLike)");
  const py::object path = py::module_::import("os").attr("fspath")(value);
  if (!PyUnicode_Check(path.ptr())) wrong_type(value, name, "a file name (str or os.PathLike)");
  const std::string text = path.cast<std::string>();
  if (text.empty()) throw py::value_error(std::string(name) + ": an empty file name");
  return text;
}

std::vector<double> reals_arg(py::handle value, const char* name) {
  if (PyUnicode_Check(value.ptr()) || PyBytes_Check(value.ptr())) wrong_type(value, name, "a sequence of numbers");
  py::object array;
  try {
    array = py::module_::import("numpy").attr("asarray")(value, "dtype"_a = "float64");
  } catch (const py::error_already_set&) {
    wrong_type(value, name, "a sequence of numbers");
  }
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);  // a column view too
  if (!a || a.ndim() != 1) wrong_type(value, name, "a sequence of numbers");
  return {a.data(), a.data() + a.size()};
}

void add_python_names(const std::vector<std::string>& names) {
  for (std::string n : names)
    if (n.find('_') != std::string::npos) {
      for (char& c : n)
        if (c == '_') c = '-';
      hyphenated().insert(n);
    }
}

std::string python_words(const std::string& message) {
  std::string out;
  out.reserve(message.size());
  for (std::size_t i = 0; i < message.size();) {
    if (i > 0 && word_char(message[i - 1])) {  // inside a word: copy on
      out += message[i++];
      continue;
    }
    const bool option = message.compare(i, 2, "--") == 0 && i + 2 < message.size() &&
                        std::islower(static_cast<unsigned char>(message[i + 2])) != 0;
    const std::size_t start = option ? i + 2 : i;
    std::size_t end = start;
    while (end < message.size() && word_char(message[end])) ++end;
    std::string word = message.substr(start, end - start);
    if (option || hyphenated().count(word) != 0)
      for (char& c : word)
        if (c == '-') c = '_';
    if (word.empty()) {
      out += message[i++];
      continue;
    }
    out += word;
    i = end;
  }
  return out;
}

void translate_library_errors() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      std::rethrow_exception(p);
    } catch (const DatabaseError& e) {
      PyErr_SetString(store_error(), python_words(e.what()).c_str());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, python_words(e.what()).c_str());
    }
  });
}

}  // namespace softdrop::python
