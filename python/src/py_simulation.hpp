#pragma once
/// \file
/// The Python-side Simulation (the façade plus its caches and the one-call-at-a-time guard)
/// and Snapshot, shared by the binding files: module.cpp (loading, stepping, signals),
/// state_views.cpp (the NumPy views and writing the state), queries.cpp (contacts and rays),
/// snapshots.cpp (pickling), images.cpp (the cameras' images), free_view.cpp (sim.render).

#include "errors.hpp"
#include "headless_camera_renderer.hpp"

#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace s2sim::python {

/// A vector and a 3×3 matrix as new NumPy arrays.
inline pybind11::array_t<double> vec3(const Vec3& v) {
  pybind11::array_t<double> a(3);
  auto w = a.mutable_unchecked<1>();
  w(0) = v.x;
  w(1) = v.y;
  w(2) = v.z;
  return a;
}

inline pybind11::array_t<double> mat3(const Mat3& m) {
  pybind11::array_t<double> a({3, 3});
  auto w = a.mutable_unchecked<2>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      w(r, c) = m.m[r][c];
  return a;
}

/// The search path of a Simulation given no plugin_path (module.cpp).
std::vector<std::filesystem::path> default_plugin_path();

/// What draws a Python Simulation's pictures (free_view.cpp): one headless renderer shared by
/// its cameras and sim.render, made at the first of either, and each camera's shot as it last
/// drew, by the address of its images (what sim.render(camera=) takes the optics from).
struct PyRendering {
  std::unique_ptr<CameraRenderer> renderer;
  std::string error;  ///< why the renderer could not be made, once it could not
  std::unordered_map<const Image*, CameraShot> shots;
  /// One shot at a time: the context is current on one thread (cameras stepped on several).
  std::mutex mutex;

  /// The renderer, made on first use; throws s2sim::Error (runtime) when it cannot be. Called
  /// with `mutex` held.
  CameraRenderer& get(const Simulation& sim);
};

/// The kernel's factory over `rendering`: each camera frame drawn by the shared renderer,
/// its shot recorded.
CameraRendererFactory shared_renderer_factory(std::shared_ptr<PyRendering> rendering);

/// A snapshot as Python sees it: restorable into the simulation it came from or another of the
/// same scene and options; pickled and saved through snapshots.cpp.
struct PySnapshot {
  Simulation::Snapshot snapshot;
  double time_s = 0;
};

/// The façade plus what the Python side caches: the signal indices of each pattern asked
/// (globbing every call would dominate a tight learning loop), the bodies' and axes' names.
class PySimulation {
 public:
  PySimulation(const std::filesystem::path& scene, std::uint64_t seed,
               std::optional<double> physics_step_s, std::optional<int> substeps,
               const std::map<std::string, double>& defines,
               const std::vector<std::filesystem::path>& plugin_path, int threads,
               bool simbody_dynamics, bool run_ahead, bool check_dynamics,
               std::optional<int> runtime_things) {
    SimulationOptions options;
    options.runtime_things = runtime_things;
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
      pybind11::gil_scoped_release release;
      sim_ = Simulation::load(scene, options);
    }
    sim_->set_camera_renderer(shared_renderer_factory(rendering_));
    const auto& sc = sim_->scene();
    for (int b = 0; b < sim_->body_count(); ++b)
      body_names_.push_back(sim_->body_path(b));
    for (std::size_t i = 0; i < body_names_.size(); ++i)
      body_by_name_.emplace(body_names_[i], static_cast<int>(i));
    for (std::size_t r = 0; r < sc.robots.size(); ++r)
      if (sc.robots[r].main_body >= 0)  // a robot by its own name: its main body
        body_by_name_.emplace("robots/" + sc.robots[r].id, sc.robots[r].main_body + 1);
    for (std::size_t a = 0; a < sim_->axis_count(); ++a)
      axis_names_.push_back(sim_->axis_path(a));
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
    pybind11::gil_scoped_release release;
    sim_->step(ticks);
  }
  void run_until(double t_s) {
    if (!std::isfinite(t_s))
      throw Error(ErrorKind::usage, "run_until(t): t must be finite, got " + std::to_string(t_s));
    Exclusive own(*this, "run_until()");
    pybind11::gil_scoped_release release;
    sim_->run_until(t_s);
  }
  void reset(std::optional<std::uint64_t> seed) {
    Exclusive own(*this, "reset()");
    pybind11::gil_scoped_release release;
    if (seed)
      sim_->reset(*seed);
    else
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
  pybind11::array_t<double> signals(const Patterns& pattern) {
    const auto& indices = match(pattern);
    pybind11::array_t<double> out(static_cast<pybind11::ssize_t>(indices.size()));
    auto view = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < indices.size(); ++i)
      view(static_cast<pybind11::ssize_t>(i)) = sim().signal(indices[i]);
    return out;
  }

  std::vector<std::string> signal_names(const std::string& pattern) {
    std::vector<std::string> names;
    for (std::size_t i : sim().match_signals(pattern))
      names.push_back(sim_->signal_info(i).name);
    return names;
  }

  int body_index(const pybind11::object& body) const {
    if (pybind11::isinstance<pybind11::int_>(body)) {
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
  const std::vector<std::string>& axis_names() const { return axis_names_; }
  /// An axis by index or by its path (`robots/<robot>/axes/<axis>`), naming the culprit.
  std::size_t axis_index(const pybind11::handle& axis) const;
  /// An input by name, naming it (with the kernel's "did you mean").
  std::size_t input_index(const std::string& name) const { return sim().input_index(name); }
  /// The renderer of the cameras and of sim.render (free_view.cpp).
  PyRendering& rendering() { return *rendering_; }

 private:
  void refuse_if_busy() const {
    // Read and written only with the GIL held: no other synchronisation is needed.
    if (busy_with_)
      throw Error(ErrorKind::usage,
                  std::string("this Simulation is in use by another thread (") + busy_with_ +
                      " has not returned): one Simulation takes one call at a time; give each "
                      "thread its own Simulation");
  }

  // Before sim_, so that it goes after it: the kernel's renderer forwards to it.
  std::shared_ptr<PyRendering> rendering_ = std::make_shared<PyRendering>();
  std::unique_ptr<Simulation> sim_;
  const char* busy_with_ = nullptr;  // the GIL-releasing call that owns the simulation
  std::unordered_map<std::string, std::vector<std::size_t>> matches_;
  std::vector<std::string> body_names_;
  std::vector<std::string> axis_names_;
  std::unordered_map<std::string, int> body_by_name_;
};

using PySimulationClass = pybind11::class_<PySimulation>;

/// The NumPy views of the state, set_state, set_inputs, place_body, reset(seed) (state_views.cpp).
void bind_state(PySimulationClass& cls);
/// Contacts and ray casts (queries.cpp).
void bind_queries(PySimulationClass& cls);
/// image_names, image(name), image_frame(name) (images.cpp).
void bind_images(PySimulationClass& cls);
/// render: a free view or a camera's, drawn between steps (free_view.cpp).
void bind_render(PySimulationClass& cls);
/// Snapshot's pickling and its construction from parts (snapshots.cpp).
void bind_snapshot(pybind11::class_<PySnapshot>& cls);

}  // namespace s2sim::python
