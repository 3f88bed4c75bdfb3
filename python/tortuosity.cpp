// softdrop.tortuosity: the pore space's geometric, diffusive and hydrodynamic tortuosities (and the
// permeability) of a medium or of a
// binary image (True in the pore space, rows from the top: PoreSpy's convention and
// Medium.to_image's), with their fields as numpy arrays.
#include <pybind11/numpy.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "studies/pore_tortuosity.hpp"

namespace softdrop::python {
namespace {

// A field of the image (rows from the bottom) as a 2D array with rows from the top.
py::array_t<double> field(const PoreImage& im, const std::vector<double>& values) {
  py::array_t<double> a({static_cast<py::ssize_t>(im.ny), static_cast<py::ssize_t>(im.nx)});
  auto v = a.mutable_unchecked<2>();
  for (int j = 0; j < im.ny; ++j)
    for (int i = 0; i < im.nx; ++i) v(im.ny - 1 - j, i) = values[static_cast<std::size_t>(i + im.nx * j)];
  return a;
}

py::dict measure(const PoreImage& im, bool flow, int buffer_rows) {
  GeometricTortuosity g;
  DiffusiveTortuosity d;
  HydrodynamicTortuosity h;
  {
    py::gil_scoped_release release;
    g = geometric_tortuosity(im);
    d = diffusive_tortuosity(im);
    if (flow) {
      FlowOptions o;
      o.buffer_rows = buffer_rows;
      h = hydrodynamic_tortuosity(im, o);
    }
  }
  py::dict out;
  out["pixel"] = im.pixel;
  out["porosity"] = im.porosity();
  out["geometric_tortuosity"] = g.tortuosity;
  out["geometric_standard_error"] = g.standard_error;
  out["starts"] = g.starts;
  out["connected"] = g.connected;
  out["diffusive_tortuosity"] = d.tau;
  out["formation_factor"] = d.formation_factor;
  out["effective_diffusivity"] = d.effective_diffusivity;
  out["distance"] = field(im, g.distance);
  out["concentration"] = field(im, d.concentration);
  if (flow) {
    out["hydrodynamic_tortuosity"] = h.tortuosity;
    out["permeability"] = h.permeability;
    out["buffer_rows"] = h.buffer_rows;
    out["velocity_x"] = field(im, h.ux);
    out["velocity_y"] = field(im, h.uy);
    out["pressure"] = field(im, h.pressure);
  }
  return out;
}

}  // namespace

void bind_tortuosity(py::module_& m) {
  m.def(
      "_tortuosity_of_medium",
      [](const Medium& medium, int pixels, bool flow, int buffer_rows) {
        return measure(pore_image(medium, pixels), flow, buffer_rows);
      },
      py::arg("medium"), py::arg("pixels"), py::arg("flow"), py::arg("buffer_rows"));
  m.def(
      "_tortuosity_of_image",
      [](const py::array& image, double pixel_size, bool periodic, bool flow, int buffer_rows) {
        const PoreImage im = pore_image_of(image, pixel_size, periodic);
        return measure(im, flow, buffer_rows);
      },
      py::arg("image"), py::arg("pixel_size"), py::arg("periodic"), py::arg("flow"), py::arg("buffer_rows"));
}

}  // namespace softdrop::python
