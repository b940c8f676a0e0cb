// Error translation: the kind of an s2sim::Error picks the Python class; the location parts and
// the bare message are attributes, so a caller can react to the file or attribute at fault.
#include "errors.hpp"

#include <s2sim/error.hpp>

#include <exception>

namespace py = pybind11;

namespace s2sim::python {

namespace {
// Owned by the module object (module attributes); the translator runs while it is alive.
PyObject* error_base = nullptr;
PyObject* error_by_kind[4] = {nullptr, nullptr, nullptr, nullptr};

const char* kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::scene:
      return "scene";
    case ErrorKind::plugin:
      return "plugin";
    case ErrorKind::usage:
      return "usage";
    case ErrorKind::runtime:
      return "runtime";
  }
  return "runtime";
}
}  // namespace

void register_errors(py::module_& m) {
  error_base = PyErr_NewExceptionWithDoc(
      "s2sim.Error",
      "An error of the simulator. str() is the located message 'file: element@attribute: "
      "message'; attributes: kind ('scene', 'plugin', 'usage', 'runtime'), file, element, "
      "attribute, message (without the location).",
      PyExc_RuntimeError, nullptr);
  m.attr("Error") = py::handle(error_base);
  const struct {
    ErrorKind kind;
    const char* name;
    const char* qualified;
    const char* doc;
  } kinds[] = {
      {ErrorKind::scene, "SceneError", "s2sim.SceneError", "Bad scene input (runner exit 2)."},
      {ErrorKind::plugin, "PluginError", "s2sim.PluginError",
       "A plugin could not be loaded or refused its parameters (runner exit 3)."},
      {ErrorKind::usage, "UsageError", "s2sim.UsageError",
       "A bad request: unknown signal or input, bad value (runner exit 4)."},
      {ErrorKind::runtime, "SimulationError", "s2sim.SimulationError",
       "The simulation failed while running, e.g. a non-finite state (runner exit 5)."},
  };
  for (const auto& k : kinds) {
    PyObject* cls = PyErr_NewExceptionWithDoc(k.qualified, k.doc, error_base, nullptr);
    error_by_kind[static_cast<int>(k.kind)] = cls;
    m.attr(k.name) = py::handle(cls);
  }

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      PyObject* cls = error_by_kind[static_cast<int>(e.kind())];
      py::object exc = py::reinterpret_steal<py::object>(PyObject_CallFunction(cls, "s", e.what()));
      if (!exc) return;  // the Python error of the failed call stays set
      exc.attr("kind") = kind_name(e.kind());
      exc.attr("file") = e.where().file;
      exc.attr("element") = e.where().element;
      exc.attr("attribute") = e.where().attribute;
      exc.attr("message") = e.message();
      PyErr_SetObject(cls, exc.ptr());
    }
  });
}

}  // namespace s2sim::python
