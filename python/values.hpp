#pragma once
// Value semantics for the module's parameter types: pickling (so they cross to multiprocessing,
// joblib and Optuna workers), copy and deepcopy (through pickling's state), equality, and a repr
// that reads back, naming only what differs from the defaults: softdrop.DropletParams(radius=5.0).
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace softdrop::python {

namespace py = pybind11;

/// Adds __getstate__/__setstate__ (a dict of `fields`), __eq__ and __repr__ to `cls`, whose
/// attributes `fields` are read-write and whose default construction is T{}.
template <class T>
void def_value_semantics(py::class_<T>& cls, std::vector<std::string> fields, const std::string& name) {
  cls.def(py::pickle(
      [fields](py::object self) {
        py::dict state;
        for (const std::string& f : fields) state[f.c_str()] = self.attr(f.c_str());
        return state;
      },
      [fields, name](const py::dict& state) {
        py::object made = py::cast(T{});
        for (const auto& [key, value] : state) {
          const std::string f = py::str(key);
          if (!py::hasattr(made, f.c_str())) throw std::invalid_argument(f + ": not a parameter of " + name);
          py::setattr(made, f.c_str(), value);
        }
        return made.cast<T>();
      }));
  cls.def("__eq__", [fields](py::object self, py::object other) {
    if (!py::isinstance(other, self.get_type())) return false;
    for (const std::string& f : fields)
      if (self.attr(f.c_str()).not_equal(other.attr(f.c_str()))) return false;
    return true;
  });
  cls.attr("__hash__") = py::none();  // mutable: not hashable, as a dataclass with eq
  cls.def("__repr__", [fields, name](py::object self) {
    const py::object defaults = py::cast(T{});
    std::string out = "softdrop." + name + "(";
    bool first = true;
    for (const std::string& f : fields) {
      const py::object v = self.attr(f.c_str());
      if (v.equal(defaults.attr(f.c_str()))) continue;
      out += (first ? "" : ", ") + f + "=" + std::string(py::repr(v));
      first = false;
    }
    return out + ")";
  });
}

}  // namespace softdrop::python
