// Images as NumPy arrays that change in place (views over the kernel's pixels, read-only): a
// camera's colour, depth and segmentation, a lidar's range image and point cloud.
#include "py_simulation.hpp"

#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;

namespace s2sim::python {
namespace {

template <class T>
py::array view_of(const Image& image, std::vector<py::ssize_t> shape,
                  std::vector<py::ssize_t> strides, py::handle owner) {
  py::array_t<T> view(std::move(shape), std::move(strides), reinterpret_cast<const T*>(image.data),
                      owner);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

/// A read-only array over the image's pixels: H×W×3 uint8 (rgb8), H×W float32, H×W uint16 or
/// H×W×3 float32 (points); `owner` (the Python Simulation) stays alive while the array does.
/// The pixels are allocated at load and never move, so the view never dangles.
py::array image_view(const Image& image, py::handle owner) {
  const py::ssize_t h = image.height_px, w = image.width_px, row = image.stride_bytes;
  switch (image.format) {
    case PixelFormat::rgb8:
      return view_of<std::uint8_t>(image, {h, w, 3}, {row, 3, 1}, owner);
    case PixelFormat::float32:
      return view_of<float>(image, {h, w}, {row, 4}, owner);
    case PixelFormat::uint16:
      return view_of<std::uint16_t>(image, {h, w}, {row, 2}, owner);
    case PixelFormat::xyz_float32:
      return view_of<float>(image, {h, w, 3}, {row, 12, 4}, owner);
  }
  throw Error(ErrorKind::usage, "an image of unknown pixel format");
}

}  // namespace

void bind_images(PySimulationClass& cls) {
  cls.def_property_readonly(
         "image_names", [](const PySimulation& s) { return s.sim().image_names(); },
         "The images the components declare (cameras, lidars), by full name.")
      .def(
          "image",
          [](py::object self, const std::string& name) {
            const PySimulation& s = self.cast<const PySimulation&>();
            return image_view(s.sim().image(name), self);
          },
          py::arg("name"),
          "The image `name` as a read-only NumPy array over the simulation's pixels, which "
          "change in place at each frame: H×W×3 uint8 (colour), H×W float32 (depth or range "
          "in metres), H×W uint16 (body ids), H×W×3 float32 (points). Copy it (np.array) to "
          "keep a frame.")
      .def(
          "image_frame",
          [](const PySimulation& s, const std::string& name) { return s.sim().image(name).frame; },
          py::arg("name"), "How many frames the image has had since the load or the last reset.");
}

}  // namespace s2sim::python
