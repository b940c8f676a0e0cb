// The pybind11 module s2sim._s2sim: the Simulation façade for Python. Names follow the façade
// (kernel/include/s2sim/kernel/simulation.hpp); values are SI as in the signal names
// (docs/signals.md). The GIL is released while the simulation loads and steps, so that other
// Python threads (a remote client, a Dask worker's heartbeat) run meanwhile.
#include "errors.hpp"
#include "py_simulation.hpp"

#include <s2sim/kernel/simulation.hpp>
#include <s2sim/version.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace s2sim::python {

namespace {

/// Plugin folders found next to the package (set by s2sim/__init__.py): build/plugins in the
/// build tree, <prefix>/lib/s2sim/plugins when installed. The kernel's own default looks next
/// to the executable, which for Python is the interpreter's folder.
std::vector<std::filesystem::path>& package_plugin_dirs() {
  static std::vector<std::filesystem::path> dirs;
  return dirs;
}

}  // namespace

/// The search path of a Simulation given no plugin_path: S2SIM_PLUGIN_PATH's folders, then the
/// package's; empty (the kernel's default) when there are none.
std::vector<std::filesystem::path> default_plugin_path() {
  std::vector<std::filesystem::path> out;
  if (const char* env = std::getenv("S2SIM_PLUGIN_PATH")) {
    const std::string value = env;
    for (std::size_t start = 0; start <= value.size();) {
      std::size_t end = value.find(':', start);
      if (end == std::string::npos) end = value.size();
      if (end > start) out.emplace_back(value.substr(start, end - start));
      start = end + 1;
    }
  }
  for (const auto& dir : package_plugin_dirs())
    out.push_back(dir);
  return out;
}

}  // namespace s2sim::python

PYBIND11_MODULE(_s2sim, m) {
  using namespace s2sim;
  using namespace s2sim::python;
  m.doc() = "S2Sim's simulation façade (docs/python.md).";
  m.attr("sdk_version") = kSdkVersionString;
  register_errors(m);
  m.def(
      "_set_package_plugin_dirs",
      [](const std::vector<std::filesystem::path>& dirs) { package_plugin_dirs() = dirs; },
      "Called by s2sim/__init__.py with the plugin folders next to the package.");

  py::class_<PySnapshot> snapshot(
      m, "Snapshot",
      "The whole state of a simulation (Simulation.save()); restore it with "
      "Simulation.restore() into the simulation it came from or into another of the same scene "
      "and options. Pickles (to a Dask worker, say), and saves to a file (save(path), "
      "Snapshot.load(path)).");
  bind_snapshot(snapshot);
  snapshot.def_property_readonly("time", [](const PySnapshot& s) { return s.time_s; })
      .def_property_readonly("layout", [](const PySnapshot& s) { return s.snapshot.layout; })
      .def_property_readonly("values", [](const PySnapshot& s) {
        return py::array_t<double>(static_cast<py::ssize_t>(s.snapshot.values.size()),
                                   s.snapshot.values.data());
      });

  PySimulationClass simulation(m, "Simulation",
                               "A loaded scene ready to step (docs/python.md). Simulation(scene, "
                               "seed=1, physics_step=None, substeps=None, defines={}, "
                               "plugin_path=[], threads=1, simbody_dynamics=False, run_ahead=True, "
                               "check_dynamics=False, runtime_things=None).");
  bind_state(simulation);
  bind_queries(simulation);
  bind_images(simulation);
  bind_render(simulation);
  simulation
      .def(py::init<const std::filesystem::path&, std::uint64_t, std::optional<double>,
                    std::optional<int>, const std::map<std::string, double>&,
                    const std::vector<std::filesystem::path>&, int, bool, bool, bool,
                    std::optional<int>>(),
           py::arg("scene"), py::arg("seed") = 1, py::arg("physics_step") = py::none(),
           py::arg("substeps") = py::none(), py::arg("defines") = std::map<std::string, double>{},
           py::arg("plugin_path") = std::vector<std::filesystem::path>{}, py::arg("threads") = 1,
           py::arg("simbody_dynamics") = false, py::arg("run_ahead") = true,
           py::arg("check_dynamics") = false, py::arg("runtime_things") = py::none())
      .def("step", &PySimulation::step, py::arg("n") = 1,
           "Advances n ticks (physics steps); the GIL is released meanwhile.")
      .def("run_until", &PySimulation::run_until, py::arg("t"),
           "Steps until time >= t seconds (rounded to the nearest tick).")
      .def_property_readonly(
          "time", [](const PySimulation& s) { return s.sim().time_s(); }, "Simulated time, s.")
      .def_property_readonly("tick", [](const PySimulation& s) { return s.sim().tick(); })
      .def_property_readonly(
          "dynamics", [](const PySimulation& s) { return s.sim().dynamics(); },
          "The dynamics that step the scene: 'tree', 'simbody', 'checked' or 'loose' "
          "(docs/models/multibody.md, 'The dynamics and their check').")
      .def_property_readonly(
          "dynamics_check",
          [](const PySimulation& s) {
            const Simulation::DynamicsCheck c = s.sim().dynamics_check();
            py::dict d;
            d["compared"] = c.compared;
            d["worst_relative"] = c.worst_relative;
            d["worst_time"] = c.worst_time_s;
            d["agreement"] = c.agreement;
            d["judged_on_loops"] = c.judged_on_loops;
            d["worst_loop_error"] = c.worst_loop_error;
            d["worst_reference_loop_error"] = c.worst_reference_loop_error;
            return d;
          },
          "With check_dynamics: the accelerations compared with Simbody's, the largest "
          "difference relative to the largest acceleration, when, the agreement allowed, and "
          "on loops the substeps judged after moving both onto the loop constraints with the "
          "largest loop errors of the tree's and Simbody's.")
      .def_property_readonly(
          "run_ahead_counts",
          [](const PySimulation& s) {
            const Simulation::RunAheadCounts c = s.sim().run_ahead_counts();
            py::dict d;
            d["stretches"] = c.stretches;
            d["ticks"] = c.ticks;
            d["lost"] = c.lost;
            return d;
          },
          "With threads > 1: stretches of ticks the parts ran ahead and kept, their ticks, and "
          "the stretches gone back (docs/scheduling.md, 'Running ahead').")
      .def_property_readonly(
          "tick_s", [](const PySimulation& s) { return s.sim().tick_s(); },
          "Length of one tick (the physics step), s.")
      .def_property_readonly(
          "control_period",
          [](const PySimulation& s) { return s.sim().scene().settings.control_period_s; },
          "The scene's control period, s.")
      .def_property_readonly("warnings", [](const PySimulation& s) { return s.sim().warnings(); })
      .def(
          "set_input",
          [](PySimulation& s, const std::string& name, double value) {
            s.sim().set_input(name, value);
          },
          py::arg("name"), py::arg("value"),
          "Sets an input; it holds until set again. A value outside the input's valid range "
          "(docs/plugins.md, \"Input ranges\") raises UsageError naming it.")
      .def(
          "input",
          [](PySimulation& s, const std::string& name) {
            return s.sim().input(s.sim().input_index(name));
          },
          py::arg("name"))
      .def(
          "signal", [](PySimulation& s, const std::string& name) { return s.sim().signal(name); },
          py::arg("name"), "The current value of a signal by name.")
      .def("signals", &PySimulation::signals<std::string>, py::arg("pattern"),
           "The values of the signals matching a glob (* any run, ? one character), in "
           "list_signals() order, as a NumPy array.")
      .def("signals", &PySimulation::signals<std::vector<std::string>>, py::arg("patterns"),
           "The values for a list of names or globs, in the list's order, as one NumPy array.")
      .def("signal_names", &PySimulation::signal_names, py::arg("pattern") = "*",
           "The names signals(pattern) returns values of, in order.")
      .def(
          "list_signals",
          [](const PySimulation& s) {
            std::vector<std::string> names;
            for (std::size_t i = 0; i < s.sim().signal_count(); ++i)
              names.push_back(s.sim().signal_info(i).name);
            return names;
          },
          "Every signal's name.")
      .def(
          "list_inputs",
          [](const PySimulation& s) {
            std::vector<std::string> names;
            for (std::size_t i = 0; i < s.sim().input_count(); ++i)
              names.push_back(s.sim().input_info(i).name);
            return names;
          },
          "Every input's name.")
      .def(
          "unit",
          [](PySimulation& s, const std::string& name) {
            return s.sim().signal_info(s.sim().signal_index(name)).unit;
          },
          py::arg("name"), "The unit of a signal (or input).")
      .def(
          "save",
          [](const PySimulation& s) {
            return PySnapshot{s.sim().save(), s.sim().time_s()};
          },
          "A copy of the whole state.")
      .def(
          "restore",
          [](PySimulation& s, const PySnapshot& snap) { s.sim().restore(snap.snapshot); },
          py::arg("snapshot"), "Continues exactly from a snapshot of this simulation.")
      .def(
          "reset", [](PySimulation& s, std::optional<std::uint64_t> seed) { s.reset(seed); },
          py::arg("seed") = py::none(),
          "Back to t = 0; a reset run repeats the first bit for bit. seed: a new seed for every "
          "component's random stream (sensor noise), kept by later resets; the same seed gives "
          "the same run.")
      .def_property_readonly(
          "seed", [](const PySimulation& s) { return s.sim().seed(); },
          "The seed of the random streams (the constructor's, or the last reset(seed)'s).")
      .def("body_names", &PySimulation::body_names,
           "Bodies by index: 0 'world', then robots/<robot>/solids/<id> and things/<id>.")
      .def(
          "body_pose",
          [](const PySimulation& s, const py::object& body) {
            const Pose& p = s.sim().body_pose(s.body_index(body));
            return py::make_tuple(vec3(p.position), mat3(p.rotation));
          },
          py::arg("body"),
          "(position [m], rotation 3x3) of a body frame in the world; body by index or name "
          "(robots/<robot> is the robot's main body).")
      .def(
          "body_twist",
          [](const PySimulation& s, const py::object& body) {
            const Twist& t = s.sim().body_twist(s.body_index(body));
            return py::make_tuple(vec3(t.linear_m_s), vec3(t.angular_rad_s));
          },
          py::arg("body"), "(linear velocity [m/s], angular velocity [rad/s]), world frame.");
}
