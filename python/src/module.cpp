// The pybind11 module s2sim._s2sim: the Simulation façade for Python. Names follow the façade
// (kernel/include/s2sim/kernel/simulation.hpp); values are SI as in the signal names
// (docs/signals.md). The GIL is released while the simulation loads and steps, so that other
// Python threads (a remote client, a Dask worker's heartbeat) run meanwhile.
#include "errors.hpp"

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

/// A snapshot as Python sees it: opaque, restorable into the simulation it came from.
struct PySnapshot {
  Simulation::Snapshot snapshot;
  double time_s = 0;
};

/// The façade plus what the Python side caches: the signal indices of each pattern asked
/// (globbing every call would dominate a tight learning loop) and the bodies' names.
class PySimulation {
 public:
  PySimulation(const std::filesystem::path& scene, std::uint64_t seed,
               std::optional<double> physics_step_s, std::optional<int> substeps,
               const std::map<std::string, double>& defines,
               const std::vector<std::filesystem::path>& plugin_path, int threads,
               bool simbody_dynamics, bool run_ahead, bool check_dynamics) {
    SimulationOptions options;
    options.seed = seed;
    options.threads = threads;
    options.run_ahead = run_ahead;
    options.simbody_dynamics_only = simbody_dynamics;
    options.check_dynamics = check_dynamics;
    options.physics_step_s = physics_step_s;
    options.substeps = substeps;
    options.plugin_path = plugin_path.empty() ? default_plugin_path() : plugin_path;
    for (const auto& [name, value] : defines)
      options.constants.emplace_back(name, value);
    {
      py::gil_scoped_release release;
      sim_ = Simulation::load(scene, options);
    }
    const auto& sc = sim_->scene();
    body_names_.push_back("world");
    for (const auto& body : sc.bodies)
      body_names_.push_back(body.robot >= 0
                                ? "robots/" + sc.robots[body.robot].id + "/solids/" + body.id
                                : "things/" + body.id);
    for (std::size_t i = 0; i < body_names_.size(); ++i)
      body_by_name_.emplace(body_names_[i], static_cast<int>(i));
    for (std::size_t r = 0; r < sc.robots.size(); ++r)
      if (sc.robots[r].main_body >= 0)  // a robot by its own name: its main body
        body_by_name_.emplace("robots/" + sc.robots[r].id, sc.robots[r].main_body + 1);
  }

  /// The simulation, for a call that holds the GIL throughout: refused while another thread
  /// runs one that released it (Exclusive).
  Simulation& sim() {
    refuse_if_busy();
    return *sim_;
  }
  const Simulation& sim() const {
    refuse_if_busy();
    return *sim_;
  }

  /// A call that releases the GIL (load, step, run_until, reset) owns the simulation until it
  /// returns: constructed before the release and destroyed after the GIL is taken back, so that
  /// any other thread's call in between sees the simulation busy and gets a clear error instead
  /// of a torn state or a crash. Several Simulations on several threads run at once.
  class Exclusive {
   public:
    Exclusive(PySimulation& s, const char* what) : s_(s) {
      s_.refuse_if_busy();
      s_.busy_with_ = what;
    }
    ~Exclusive() { s_.busy_with_ = nullptr; }
    Exclusive(const Exclusive&) = delete;
    Exclusive& operator=(const Exclusive&) = delete;

   private:
    PySimulation& s_;
  };

  void step(std::int64_t ticks) {
    if (ticks < 0)
      throw Error(ErrorKind::usage, "step(n): n must be >= 0, got " + std::to_string(ticks));
    Exclusive own(*this, "step()");
    py::gil_scoped_release release;
    sim_->step(ticks);
  }
  void run_until(double t_s) {
    if (!std::isfinite(t_s))
      throw Error(ErrorKind::usage, "run_until(t): t must be finite, got " + std::to_string(t_s));
    Exclusive own(*this, "run_until()");
    py::gil_scoped_release release;
    sim_->run_until(t_s);
  }
  void reset() {
    Exclusive own(*this, "reset()");
    py::gil_scoped_release release;
    sim_->reset();
  }

  const std::vector<std::size_t>& match(const std::string& pattern) {
    auto it = matches_.find(pattern);
    if (it != matches_.end()) return it->second;
    std::vector<std::size_t> found = sim().match_signals(pattern);
    if (found.empty()) {
      // An exact name that is not there deserves the façade's "did you mean".
      if (pattern.find_first_of("*?") == std::string::npos) (void)sim_->signal_index(pattern);
      throw Error(ErrorKind::usage, "no signal matches '" + pattern + "'");
    }
    return matches_.emplace(pattern, std::move(found)).first->second;
  }

  /// The indices of several patterns, one after another (cached under their joined text).
  const std::vector<std::size_t>& match(const std::vector<std::string>& patterns) {
    std::string key = "\n";  // no single pattern starts with a newline
    for (const auto& p : patterns)
      key += p + "\n";
    auto it = matches_.find(key);
    if (it != matches_.end()) return it->second;
    std::vector<std::size_t> all;
    for (const auto& p : patterns) {
      const auto& found = match(p);
      all.insert(all.end(), found.begin(), found.end());
    }
    return matches_.emplace(key, std::move(all)).first->second;
  }

  template <class Patterns>
  py::array_t<double> signals(const Patterns& pattern) {
    const auto& indices = match(pattern);
    py::array_t<double> out(static_cast<py::ssize_t>(indices.size()));
    auto view = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < indices.size(); ++i)
      view(static_cast<py::ssize_t>(i)) = sim().signal(indices[i]);
    return out;
  }

  std::vector<std::string> signal_names(const std::string& pattern) {
    std::vector<std::string> names;
    for (std::size_t i : sim().match_signals(pattern))
      names.push_back(sim_->signal_info(i).name);
    return names;
  }

  int body_index(const py::object& body) const {
    if (py::isinstance<py::int_>(body)) {
      const int index = body.cast<int>();
      if (index < 0 || index >= sim().body_count())
        throw Error(ErrorKind::usage, "body index " + std::to_string(index) +
                                          " is out of range (0 to " +
                                          std::to_string(sim_->body_count() - 1) + ")");
      return index;
    }
    const auto name = body.cast<std::string>();
    auto it = body_by_name_.find(name);
    if (it == body_by_name_.end())
      throw Error(ErrorKind::usage, "unknown body '" + name +
                                        "' (names: robots/<robot>, robots/<robot>/solids/<id>, "
                                        "things/<id>; see body_names())");
    return it->second;
  }

  const std::vector<std::string>& body_names() const { return body_names_; }

 private:
  void refuse_if_busy() const {
    // Read and written only with the GIL held: no other synchronisation is needed.
    if (busy_with_)
      throw Error(ErrorKind::usage,
                  std::string("this Simulation is in use by another thread (") + busy_with_ +
                      " has not returned): one Simulation takes one call at a time; give each "
                      "thread its own Simulation");
  }

  std::unique_ptr<Simulation> sim_;
  const char* busy_with_ = nullptr;  // the GIL-releasing call that owns the simulation
  std::unordered_map<std::string, std::vector<std::size_t>> matches_;
  std::vector<std::string> body_names_;
  std::unordered_map<std::string, int> body_by_name_;
};

py::array_t<double> vec3(const Vec3& v) {
  py::array_t<double> a(3);
  auto w = a.mutable_unchecked<1>();
  w(0) = v.x;
  w(1) = v.y;
  w(2) = v.z;
  return a;
}

py::array_t<double> mat3(const Mat3& m) {
  py::array_t<double> a({3, 3});
  auto w = a.mutable_unchecked<2>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      w(r, c) = m.m[r][c];
  return a;
}

}  // namespace

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

  py::class_<PySnapshot>(m, "Snapshot",
                         "The whole state of a simulation (Simulation.save()); restore it into "
                         "the simulation it came from with Simulation.restore().")
      .def_property_readonly("time", [](const PySnapshot& s) { return s.time_s; })
      .def_property_readonly("layout", [](const PySnapshot& s) { return s.snapshot.layout; })
      .def_property_readonly("values", [](const PySnapshot& s) {
        return py::array_t<double>(static_cast<py::ssize_t>(s.snapshot.values.size()),
                                   s.snapshot.values.data());
      });

  py::class_<PySimulation>(m, "Simulation",
                           "A loaded scene ready to step (docs/python.md). Simulation(scene, "
                           "seed=1, physics_step=None, substeps=None, defines={}, "
                           "plugin_path=[], threads=1, simbody_dynamics=False, run_ahead=True, "
                           "check_dynamics=False).")
      .def(py::init<const std::filesystem::path&, std::uint64_t, std::optional<double>,
                    std::optional<int>, const std::map<std::string, double>&,
                    const std::vector<std::filesystem::path>&, int, bool, bool, bool>(),
           py::arg("scene"), py::arg("seed") = 1, py::arg("physics_step") = py::none(),
           py::arg("substeps") = py::none(), py::arg("defines") = std::map<std::string, double>{},
           py::arg("plugin_path") = std::vector<std::filesystem::path>{}, py::arg("threads") = 1,
           py::arg("simbody_dynamics") = false, py::arg("run_ahead") = true,
           py::arg("check_dynamics") = false)
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
          py::arg("name"), py::arg("value"), "Sets an input; it holds until set again.")
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
          "reset", [](PySimulation& s) { s.reset(); },
          "Back to t = 0; a reset run repeats the first bit for bit.")
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
