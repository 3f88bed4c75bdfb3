#pragma once
// The parts of the Python module's compiled core (softdrop._core), one function each to add its
// bindings to the module.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <functional>
#include <thread>
#include <vector>

#include "softdrop/simulation.hpp"

namespace softdrop::python {

namespace py = pybind11;

/// softdrop.StoreError (a RuntimeError): a database the store refuses. Set up by bind_stores.
PyObject* store_error();

/// A batch's progress callback that stops it on Ctrl-C: the calling thread, one of the batch's
/// workers, looks for signals after each droplet it finishes (Python runs signal handlers on that
/// thread only) and throws KeyboardInterrupt through the batch, which ends the droplets in flight
/// and rethrows it. Made on the calling thread, which holds the GIL until the batch starts.
inline std::function<void(int, int)> stop_on_ctrl_c() {
  const std::thread::id caller = std::this_thread::get_id();
  return [caller](int, int) {
    if (std::this_thread::get_id() != caller) return;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  };
}

/// A path as every path softdrop gives it to Python: an (n, 2) array of rows x, y.
pybind11::array_t<double> xy_array(const std::vector<double>& x, const std::vector<double>& y);

/// Throws std::invalid_argument (ValueError in Python) naming the first bad parameter of either.
void check(const DropletParams& params, const RunOptions& run);
/// `run` with Ctrl-C in the interpreter stopping it: polled through RunOptions::cancelled (the run
/// then throws RunCancelled and *interrupted is set), with the GIL taken for the check only.
RunOptions interruptible(RunOptions run, bool* interrupted);
/// One run as Python's Result holds it: the --runs CSV's names, touched_grains, and with_path the
/// path (rows x, y) and path_time.
py::dict summary_dict(const RunSummary& s, bool with_path);

/// A 2D numpy array, rows from the top, True or 1 in the pore space, as a PoreImage (rows from
/// the bottom). Throws std::invalid_argument naming `image` or `pixel_size`: not 2D, empty, not
/// numbers, not binary, a bad pixel size.
PoreImage pore_image_of(const py::array& image, double pixel_size, bool periodic);
/// softdrop.Medium (medium.hpp).
void bind_medium(py::module_& m);
/// The held-out value of a medium (batch.hpp).
void bind_held_out(py::module_& m);
/// Two droplets one after the other (simulation.hpp, batch.hpp): simulate_pair, simulate_pairs.
void bind_two_droplets(py::module_& m);
/// The pore space's tortuosities of a medium or an image (pore_tortuosity.hpp).
void bind_tortuosity(py::module_& m);
/// The readers of search histories and sweep stores: read_history, read_sweep, best_arrangement.
void bind_stores(py::module_& m);
/// The program's optimize and sweep commands, run in this process: the same options, files and
/// messages, with a Python callback per committed generation or medium.
void bind_commands(py::module_& m);

}  // namespace softdrop::python
