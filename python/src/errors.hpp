#pragma once
/// \file
/// s2sim::Error raised in Python as s2sim.Error or one of its subclasses, one per ErrorKind
/// (SceneError, PluginError, UsageError, SimulationError), carrying the located message.

#include <pybind11/pybind11.h>

namespace s2sim::python {

/// Creates the exception classes in `module` and registers the translator.
void register_errors(pybind11::module_& module);

}  // namespace s2sim::python
