// softdrop.Medium: a box of disc grains, generated, loaded or saved as the command line does, and
// drawn as a pore image; picklable and copyable.
#include "softdrop/medium.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "arguments.hpp"
#include "bindings.hpp"
#include "studies/pore_tortuosity.hpp"
#include "values.hpp"

namespace softdrop::python {
namespace {

py::array_t<double> grain_array(const Medium& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.grains.size()), py::ssize_t{3}});
  auto v = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < m.grains.size(); ++i) {
    const auto k = static_cast<py::ssize_t>(i);
    v(k, 0) = m.grains[i].x, v(k, 1) = m.grains[i].y, v(k, 2) = m.grains[i].r;
  }
  a.attr("setflags")(py::arg("write") = false);  // a copy: a write would be lost, so it is refused
  return a;
}

// A PoreImage as a boolean array, rows from the top.
py::array_t<bool> top_first(const PoreImage& im) {
  py::array_t<bool> image({static_cast<py::ssize_t>(im.ny), static_cast<py::ssize_t>(im.nx)});
  auto v = image.mutable_unchecked<2>();
  for (int r = 0; r < im.ny; ++r)
    for (int c = 0; c < im.nx; ++c)
      v(r, c) = im.pore[static_cast<std::size_t>(c) + static_cast<std::size_t>(im.nx) * (im.ny - 1 - r)] != 0;
  return image;
}

// A boolean image of the box, rows from the top: True in the pore space (PoreSpy's convention).
py::array_t<bool> pore_array(const Medium& m, int pixels) {
  if (pixels < 1 || pixels > 20000)
    throw std::invalid_argument("pixels = " + std::to_string(pixels) + ": must be in [1, 20000]");
  if (m.image) return top_first(pixels == m.image->nx ? *m.image : softdrop::pore_image(m, pixels));
  const double scale = pixels / m.width;
  const auto rows = static_cast<py::ssize_t>(std::max(1.0, std::round(m.height * scale)));
  py::array_t<bool> image({rows, static_cast<py::ssize_t>(pixels)});
  auto v = image.mutable_unchecked<2>();
  for (py::ssize_t r = 0; r < rows; ++r)
    for (py::ssize_t c = 0; c < pixels; ++c) v(r, c) = true;
  for (const Grain& g : m.grains)  // each grain clears the pixels whose centres it covers
    for (int image_shift : {-1, 0, 1}) {
      if (image_shift != 0 && !m.periodic) continue;
      const double gx = g.x + image_shift * m.width;
      const auto c0 = std::max<py::ssize_t>(0, static_cast<py::ssize_t>(std::floor((gx - g.r) * scale)));
      const auto c1 = std::min<py::ssize_t>(pixels - 1, static_cast<py::ssize_t>(std::ceil((gx + g.r) * scale)));
      for (py::ssize_t c = c0; c <= c1; ++c) {
        const double x = (static_cast<double>(c) + 0.5) / scale - gx;
        if (std::abs(x) > g.r) continue;
        const double half = std::sqrt(g.r * g.r - x * x);
        for (py::ssize_t r = 0; r < rows; ++r) {
          const double y = m.height - (static_cast<double>(r) + 0.5) / scale;
          if (std::abs(y - g.y) <= half) v(r, c) = false;
        }
      }
    }
  return image;
}

// A kind of medium by the name the program takes (not the older spelling it still reads in files).
MediumKind medium_kind_arg(const py::object& kind) {
  const std::string name = text_arg(kind, "kind");
  const std::vector<std::string> names = medium_kind_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
      list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    throw std::invalid_argument("kind = '" + name + "': must be " + list);
  }
  return parse_medium_kind(name);
}

}  // namespace

PoreImage pore_image_of(const py::array& image, double pixel_size, bool periodic) {
  if (image.ndim() != 2) throw std::invalid_argument("image: a 2D array, not " + std::to_string(image.ndim()) + "D");
  if (image.shape(0) < 1 || image.shape(1) < 1) throw std::invalid_argument("image: empty");
  if (!(pixel_size > 0) || !std::isfinite(pixel_size))
    throw std::invalid_argument("pixel_size = " + std::string(py::repr(py::float_(pixel_size))) +
                                ": must be finite and > 0");
  const auto values = py::array_t<double, py::array::forcecast>::ensure(image);
  if (!values) throw std::invalid_argument("image: not an array of numbers");
  const auto v = values.unchecked<2>();
  PoreImage im;
  im.ny = static_cast<int>(image.shape(0));
  im.nx = static_cast<int>(image.shape(1));
  im.pixel = pixel_size;
  im.periodic = periodic;
  im.pore.resize(static_cast<std::size_t>(im.nx) * static_cast<std::size_t>(im.ny));
  for (int r = 0; r < im.ny; ++r)
    for (int c = 0; c < im.nx; ++c) {
      const double x = v(r, c);
      if (x != 0 && x != 1)
        throw std::invalid_argument("image: not binary (" + std::string(py::repr(py::float_(x))) + " at row " +
                                    std::to_string(r) + ", column " + std::to_string(c) + "); True or 1 is pore space");
      im.pore[static_cast<std::size_t>(c) + static_cast<std::size_t>(im.nx) * (im.ny - 1 - r)] = x == 1;
    }
  return im;
}

void bind_medium(py::module_& m) {
  const MediumOptions kMedium;  // the program's defaults are the module's
  py::class_<Medium>(m, "Medium", "A box of disc grains (length units)")
      .def_static(
          "generate",
          [](const py::object& kind, const py::object& porosity, const py::object& width, const py::object& height,
             const py::object& r_min, const py::object& r_max, const py::object& seed, const py::object& gap,
             const py::object& periodic, const py::object& grains) {
            MediumOptions o;
            o.kind = medium_kind_arg(kind);
            o.porosity = real_arg(porosity, "porosity"), o.width = real_arg(width, "width");
            o.height = real_arg(height, "height"), o.r_min = real_arg(r_min, "r_min");
            o.r_max = real_arg(r_max, "r_max"), o.seed = seed_arg(seed, "seed"), o.gap = real_arg(gap, "gap");
            o.periodic = bool_arg(periodic, "periodic");
            o.grains = int_arg(grains, "grains");
            std::string why;
            if (!o.IsValid(&why)) throw std::invalid_argument(why);
            py::gil_scoped_release release;
            try {
              return generate_medium(o);
            } catch (const std::runtime_error& e) {  // a target random placement cannot reach: a bad argument
              throw std::invalid_argument(e.what());
            }
          },
          py::arg("kind") = "overlapping", py::arg("porosity") = kMedium.porosity, py::arg("width") = kMedium.width,
          py::arg("height") = kMedium.height, py::arg("r_min") = kMedium.r_min, py::arg("r_max") = kMedium.r_max,
          py::arg("seed") = kMedium.seed, py::arg("gap") = kMedium.gap, py::arg("periodic") = kMedium.periodic,
          py::arg("grains") = kMedium.grains,
          "A random medium, as `softdrop simulate` generates it (the same options give the same grains). "
          "kind: overlapping, non-overlapping (random sequential addition) or relaxed (non-overlapping, "
          "placed at random and pushed apart: lower porosities with wider gaps); porosity: the target void "
          "fraction; width, height: the box (length units); r_min, r_max: the grains' radii; seed: a whole "
          "number from 0; gap: the least surface gap of non-overlapping and relaxed grains, as a fraction of the "
          "larger radius; periodic: periodic in x (else walls); grains: a fixed number of grains (0: as many as "
          "the porosity needs)")
      .def_static(
          "from_arrays",
          [](const py::object& x, const py::object& y, const py::object& r, const py::object& width,
             const py::object& height, const py::object& periodic) {
            const std::vector<double> xs = reals_arg(x, "x"), ys = reals_arg(y, "y"), rs = reals_arg(r, "r");
            if (xs.size() != ys.size() || xs.size() != rs.size())
              throw std::invalid_argument("x, y, r: must have the same length");
            Medium med;
            med.width = real_arg(width, "width"), med.height = real_arg(height, "height");
            med.periodic = bool_arg(periodic, "periodic");
            for (std::size_t i = 0; i < xs.size(); ++i) med.grains.push_back({xs[i], ys[i], rs[i]});
            std::string why;
            if (!med.IsValid(&why)) throw std::invalid_argument(why);
            return med;
          },
          py::arg("x"), py::arg("y"), py::arg("r"), py::arg("width"), py::arg("height"), py::arg("periodic") = true,
          "A medium of the grains at x, y of radii r (sequences of numbers, length units) in a box width x "
          "height, periodic in x or not")
      .def_static(
          "from_image",
          [](const py::object& image, const py::object& pixel_size, const py::object& periodic) {
            if (!py::isinstance<py::array>(image) && !py::isinstance<py::sequence>(image))
              throw py::type_error("image: a 2D array, not " + std::string(py::repr(image)));
            return image_medium(pore_image_of(py::module_::import("numpy").attr("asarray")(image),
                                              real_arg(pixel_size, "pixel_size"), bool_arg(periodic, "periodic")));
          },
          py::arg("image"), py::arg("pixel_size") = 1.0, py::arg("periodic") = true,
          "The medium of a binary image's pore space: a 2D array, rows from the top, True or 1 in the pore "
          "(PoreSpy's convention, and to_image's), pixels of side pixel_size (length units). The droplet meets "
          "its solid through a signed distance field.")
      .def_static(
          "load",
          [](const py::object& path_object, const py::object& pixel_size, const py::object& periodic) {
            const std::filesystem::path path = path_arg(path_object, "path");
            const double pixel = real_arg(pixel_size, "pixel_size");
            const bool is_periodic = bool_arg(periodic, "periodic");
            std::error_code ec;
            if (!std::filesystem::exists(path, ec)) {  // as open() says it
              const char* what = is_image_file(path.string()) ? "image" : "grain file";
              PyErr_SetString(PyExc_FileNotFoundError,
                              (std::string(what) + " '" + path.string() + "': no such file").c_str());
              throw py::error_already_set();
            }
            if (is_image_file(path.string())) return load_image_medium(path.string(), pixel, is_periodic);
            return load_medium(path.string());
          },
          py::arg("path"), py::arg("pixel_size") = 1.0, py::arg("periodic") = true,
          "Reads a grain file (.json, or CSV), or a binary image (.png, .tif, .npy: white, 1 or True is pore) "
          "whose pixels are pixel_size wide, periodic in x or not; path: str or os.PathLike")
      .def(
          "save", [](const Medium& med, const py::object& path) { save_medium(path_arg(path, "path").string(), med); },
          py::arg("path"),
          "Writes a grain file (.json, or CSV), or an image medium's image (.png, .npy); path: str or os.PathLike")
      .def_property_readonly(
          "image",
          [](const Medium& med) -> py::object { return med.image ? py::object(top_first(*med.image)) : py::none(); },
          "An image medium's pore space (rows from the top, True in the pore); None for a medium of grains")
      .def_property_readonly(
          "pixel_size",
          [](const Medium& med) -> py::object {
            return med.image ? py::object(py::float_(med.image->pixel)) : py::object(py::none());
          },
          "An image medium's pixel side (length units); None for a medium of grains")
      .def_readonly("width", &Medium::width)
      .def_readonly("height", &Medium::height)
      .def_readonly("periodic", &Medium::periodic)
      .def_property_readonly("grains", &grain_array, "N x 3 array of x, y, r")
      .def("porosity", &exact_porosity, "The exact void fraction of the box")
      .def(
          "to_image",
          [](const Medium& med, const py::object& pixels) { return pore_array(med, int_arg(pixels, "pixels")); },
          py::arg("pixels"), "Boolean image, `pixels` wide, rows from the top: True in the pore space")
      .def("__len__", [](const Medium& med) { return med.grains.size(); })
      .def("__repr__",
           [](const Medium& med) {
             if (med.image)
               return "<softdrop.Medium: image of " + std::to_string(med.image->nx) + " x " +
                      std::to_string(med.image->ny) + " pixels, " + std::string(py::repr(py::float_(med.width))) +
                      " x " + std::string(py::repr(py::float_(med.height))) +
                      (med.periodic ? ", periodic>" : ", walls>");
             return "<softdrop.Medium: " + std::to_string(med.grains.size()) + " grains, " +
                    std::string(py::repr(py::float_(med.width))) + " x " +
                    std::string(py::repr(py::float_(med.height))) + (med.periodic ? ", periodic>" : ", walls>");
           })
      .def("__eq__", [](const Medium& a, py::object b) { return py::isinstance<Medium>(b) && a == b.cast<Medium>(); })
      .def(py::pickle(  // the box and every grain, to the bit (Python floats are doubles), or the image
          [](const Medium& med) -> py::tuple {
            if (med.image)
              return py::make_tuple(
                  med.image->pixel, med.periodic,
                  py::bytes(reinterpret_cast<const char*>(med.image->pore.data()), med.image->pore.size()),
                  med.image->nx, med.image->ny);
            py::list grains;
            for (const Grain& g : med.grains) grains.append(py::make_tuple(g.x, g.y, g.r));
            return py::make_tuple(med.width, med.height, med.periodic, grains);
          },
          [](const py::tuple& state) {
            if (state.size() == 5) {  // an image medium
              PoreImage im;
              im.pixel = state[0].cast<double>();
              im.periodic = state[1].cast<bool>();
              const std::string pore = state[2].cast<std::string>();
              im.pore.assign(pore.begin(), pore.end());
              im.nx = state[3].cast<int>(), im.ny = state[4].cast<int>();
              return image_medium(std::move(im));
            }
            if (state.size() != 4) throw std::invalid_argument("Medium: a pickled state has 4 items (5 for an image)");
            Medium med;
            med.width = state[0].cast<double>(), med.height = state[1].cast<double>();
            med.periodic = state[2].cast<bool>();
            for (const auto& g : state[3].cast<py::list>()) {
              const auto t = g.cast<py::tuple>();
              med.grains.push_back({t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>()});
            }
            return med;
          }));
  py::type::of<Medium>().attr("__hash__") = py::none();
}

}  // namespace softdrop::python
