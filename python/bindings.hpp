#pragma once
// The parts of the Python module's compiled core (softdrop._core), one function each to add its
// bindings to the module.
#include <pybind11/pybind11.h>

namespace softdrop::python {

namespace py = pybind11;

/// softdrop.StoreError (a RuntimeError): a database the store refuses. Set up by bind_stores.
PyObject* store_error();

/// The readers of search histories and sweep stores: read_history, read_sweep, best_arrangement.
void bind_stores(py::module_& m);
/// The program's optimize and sweep commands, run in this process: the same options, files and
/// messages, with a Python callback per committed generation or medium.
void bind_commands(py::module_& m);

}  // namespace softdrop::python
