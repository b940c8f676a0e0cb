// The state as NumPy arrays that change in place (views over the kernel's buffers, read-only:
// writing goes through set_state, set_inputs and place_body, which the kernel checks), the name
// maps that index them, and the calls that write the state.
#include "py_simulation.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace py = pybind11;

namespace s2sim::python {

// The views below stride through these structs as arrays of doubles.
static_assert(std::is_standard_layout_v<Pose> && sizeof(Pose) == 12 * sizeof(double) &&
              offsetof(Pose, rotation) == 3 * sizeof(double));
static_assert(std::is_standard_layout_v<Twist> && sizeof(Twist) == 6 * sizeof(double) &&
              offsetof(Twist, linear_m_s) == 3 * sizeof(double));

namespace {

constexpr auto kDouble = static_cast<py::ssize_t>(sizeof(double));

/// A read-only array over kernel memory; `owner` (the Python Simulation) stays alive while the
/// array does. The kernel's buffers are sized at load and never move, so the view never dangles.
py::array read_only_view(const double* data, std::vector<py::ssize_t> shape,
                         std::vector<py::ssize_t> strides, py::handle owner) {
  py::array_t<double> view(std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

py::array vector_view(const std::vector<double>& buffer, py::handle owner) {
  return read_only_view(buffer.data(), {static_cast<py::ssize_t>(buffer.size())}, {kDouble}, owner);
}

/// One value of a dict or an array given by the user: a finite real number, else a UsageError
/// naming `what`.
double real_value(const py::handle& value, const std::string& what) {
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
      PyBool_Check(value.ptr()) || PyComplex_Check(value.ptr()))
    throw Error(ErrorKind::usage,
                what + " must be a real number, got " + py::repr(value).cast<std::string>());
  double x = 0;
  try {
    x = value.cast<double>();
  } catch (const py::cast_error&) {
    throw Error(ErrorKind::usage,
                what + " must be a real number, got " + py::repr(value).cast<std::string>());
  }
  if (!std::isfinite(x))
    throw Error(ErrorKind::usage, what + " must be finite, got " + std::to_string(x));
  return x;
}

/// A 1-D array of `n` real numbers (any real dtype; not bool, complex, strings or objects),
/// else a UsageError naming `call`, the shape or dtype given, and what `n` counts.
std::vector<double> real_array(const py::handle& given, std::size_t n, const std::string& call,
                               const std::string& counted,
                               const std::function<std::string(std::size_t)>& name_of) {
  py::array array = py::array::ensure(given);
  if (!array)
    throw Error(ErrorKind::usage, call + ": expected a dict or an array of " + std::to_string(n) +
                                      " numbers, got " + py::repr(given).cast<std::string>());
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw Error(ErrorKind::usage, call + ": the array's dtype must be a real number type, got " +
                                      py::str(array.dtype()).cast<std::string>());
  if (array.ndim() != 1 || static_cast<std::size_t>(array.shape(0)) != n) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d)
      shape += (d ? ", " : "") + std::to_string(array.shape(d));
    shape += array.ndim() == 1 ? ",)" : ")";
    throw Error(ErrorKind::usage, call + ": the array must have shape (" + std::to_string(n) +
                                      ",), one value per " + counted + ", got shape " + shape);
  }
  auto as_double = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = as_double.at(static_cast<py::ssize_t>(i));
    if (!std::isfinite(out[i]))
      throw Error(ErrorKind::usage, call + ": the value for " + name_of(i) +
                                        " must be finite, got " + std::to_string(out[i]));
  }
  return out;
}

Vec3 vec3_of(const py::handle& given, const std::string& what) {
  const auto v = real_array(given, 3, what, "coordinate (x, y, z)",
                            [&](std::size_t i) { return what + "[" + std::to_string(i) + "]"; });
  return {v[0], v[1], v[2]};
}

Mat3 matrix_of(const py::handle& given, const std::string& what) {
  py::array array = py::array::ensure(given);
  if (!array || array.ndim() != 2 || array.shape(0) != 3 || array.shape(1) != 3)
    throw Error(ErrorKind::usage,
                what + " must be a 3x3 matrix, got " + py::repr(given).cast<std::string>());
  Mat3 r;
  py::list rows = array.attr("tolist")();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = real_value(rows[i].cast<py::list>()[j],
                             what + "[" + std::to_string(i) + "][" + std::to_string(j) + "]");
  return r;
}

Mat3 rotation_of(const py::handle& given) {
  const Mat3 r = matrix_of(given, "place_body: rotation");
  double worst = 0;  // |R·Rᵀ − I|
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k)
        dot += r.m[i][k] * r.m[j][k];
      worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  const double det = r.m[0][0] * (r.m[1][1] * r.m[2][2] - r.m[1][2] * r.m[2][1]) -
                     r.m[0][1] * (r.m[1][0] * r.m[2][2] - r.m[1][2] * r.m[2][0]) +
                     r.m[0][2] * (r.m[1][0] * r.m[2][1] - r.m[1][1] * r.m[2][0]);
  if (worst > 1e-6 || det < 0)
    throw Error(ErrorKind::usage,
                "place_body: rotation must be a rotation matrix (orthonormal, determinant +1); "
                "|R·Rᵀ − I| is " +
                    std::to_string(worst) + ", the determinant " + std::to_string(det));
  return r;
}

/// Axis values from a dict (axis path or index -> value) over `current`, or a full array.
std::vector<double> axis_values(const PySimulation& s, const py::handle& given,
                                const std::vector<double>& current, const char* which) {
  const std::string call = std::string("set_state(") + which + "=...)";
  if (py::isinstance<py::dict>(given)) {
    std::vector<double> out = current;
    for (auto item : given.cast<py::dict>()) {
      const std::size_t a = s.axis_index(item.first);
      out[a] = real_value(item.second, call + ": the value for axis '" + s.axis_names()[a] + "'");
    }
    return out;
  }
  return real_array(given, current.size(), call, "axis (axis_names order)",
                    [&](std::size_t i) { return "axis '" + s.axis_names()[i] + "'"; });
}

}  // namespace

std::size_t PySimulation::axis_index(const py::handle& axis) const {
  const std::size_t count = sim().axis_count();
  if (py::isinstance<py::int_>(axis) && !PyBool_Check(axis.ptr())) {
    const auto index = axis.cast<long long>();
    if (index < 0 || static_cast<std::size_t>(index) >= count)
      throw Error(ErrorKind::usage, "axis index " + std::to_string(index) + " is out of range (" +
                                        std::to_string(count) + " axes)");
    return static_cast<std::size_t>(index);
  }
  if (!py::isinstance<py::str>(axis))
    throw Error(ErrorKind::usage, "an axis is its path (str, see axis_names) or its index, got " +
                                      py::repr(axis).cast<std::string>());
  const auto name = axis.cast<std::string>();
  for (std::size_t a = 0; a < axis_names_.size(); ++a)
    if (axis_names_[a] == name) return a;
  std::string names;
  for (const auto& n : axis_names_)
    names += (names.empty() ? "" : ", ") + n;
  throw Error(ErrorKind::usage,
              "unknown axis '" + name + "' (axes: " + (names.empty() ? "none" : names) + ")");
}

void bind_state(PySimulationClass& cls) {
  cls.def_property_readonly(
         "q",
         [](py::object self) {
           return vector_view(self.cast<PySimulation&>().sim().axis_positions(), self);
         },
         "Axis positions (rad or m) in axis_names order: a read-only view that changes in "
         "place as the simulation steps.")
      .def_property_readonly(
          "u",
          [](py::object self) {
            return vector_view(self.cast<PySimulation&>().sim().axis_velocities(), self);
          },
          "Axis velocities (rad/s or m/s) in axis_names order: a read-only view.")
      .def_property_readonly(
          "body_positions",
          [](py::object self) {
            const auto& poses = self.cast<PySimulation&>().sim().body_poses();
            return read_only_view(&poses[0].position.x, {static_cast<py::ssize_t>(poses.size()), 3},
                                  {static_cast<py::ssize_t>(sizeof(Pose)), kDouble}, self);
          },
          "Body frame origins in the world, m, shape (bodies, 3), body_names order (row 0 is "
          "the world): a read-only view.")
      .def_property_readonly(
          "body_rotations",
          [](py::object self) {
            const auto& poses = self.cast<PySimulation&>().sim().body_poses();
            return read_only_view(
                &poses[0].rotation.m[0][0], {static_cast<py::ssize_t>(poses.size()), 3, 3},
                {static_cast<py::ssize_t>(sizeof(Pose)), 3 * kDouble, kDouble}, self);
          },
          "Body frame rotations (body to world), shape (bodies, 3, 3): a read-only view.")
      .def_property_readonly(
          "body_linear_velocities",
          [](py::object self) {
            const auto& twists = self.cast<PySimulation&>().sim().body_twists();
            return read_only_view(&twists[0].linear_m_s.x,
                                  {static_cast<py::ssize_t>(twists.size()), 3},
                                  {static_cast<py::ssize_t>(sizeof(Twist)), kDouble}, self);
          },
          "Velocities of the body frame origins, world frame, m/s, shape (bodies, 3): a "
          "read-only view.")
      .def_property_readonly(
          "body_angular_velocities",
          [](py::object self) {
            const auto& twists = self.cast<PySimulation&>().sim().body_twists();
            return read_only_view(&twists[0].angular_rad_s.x,
                                  {static_cast<py::ssize_t>(twists.size()), 3},
                                  {static_cast<py::ssize_t>(sizeof(Twist)), kDouble}, self);
          },
          "Angular velocities of the bodies, world frame, rad/s, shape (bodies, 3): a "
          "read-only view.")
      .def_property_readonly(
          "signal_values",
          [](py::object self) {
            return vector_view(self.cast<PySimulation&>().sim().signal_values(), self);
          },
          "Every signal's value in list_signals() order (index with signal_ids): a read-only "
          "view, rewritten by every call that changes the state or an input.")
      .def_property_readonly(
          "input_values",
          [](py::object self) {
            return vector_view(self.cast<PySimulation&>().sim().inputs(), self);
          },
          "Every input's value in list_inputs() order (index with input_ids): a read-only "
          "view; write with set_inputs.")
      .def_property_readonly(
          "signal_ids",
          [](const PySimulation& s) {
            py::dict ids;
            for (std::size_t i = 0; i < s.sim().signal_count(); ++i)
              ids[py::str(s.sim().signal_info(i).name)] = i;
            return ids;
          },
          "Signal name -> index into signal_values.")
      .def_property_readonly(
          "input_ids",
          [](const PySimulation& s) {
            py::dict ids;
            for (std::size_t i = 0; i < s.sim().input_count(); ++i)
              ids[py::str(s.sim().input_info(i).name)] = i;
            return ids;
          },
          "Input name -> index into input_values and set_inputs' array.")
      .def_property_readonly(
          "axis_names", [](const PySimulation& s) { return s.axis_names(); },
          "Axis paths (robots/<robot>/axes/<axis>, world/axes/<axis>) in q and u order.")
      .def_property_readonly(
          "axis_ids",
          [](const PySimulation& s) {
            py::dict ids;
            for (std::size_t a = 0; a < s.axis_names().size(); ++a)
              ids[py::str(s.axis_names()[a])] = a;
            return ids;
          },
          "Axis path -> index into q and u.")
      .def_property_readonly(
          "body_ids",
          [](const PySimulation& s) {
            py::dict ids;
            for (std::size_t b = 0; b < s.body_names().size(); ++b)
              ids[py::str(s.body_names()[b])] = b;
            return ids;
          },
          "Body path -> row of body_positions, body_rotations and the velocities.")
      .def(
          "set_inputs",
          [](PySimulation& s, const py::object& values) {
            Simulation& sim = s.sim();
            std::vector<std::pair<std::size_t, double>> writes;  // all checked, then written
            if (py::isinstance<py::dict>(values)) {
              for (auto item : values.cast<py::dict>()) {
                if (!py::isinstance<py::str>(item.first))
                  throw Error(ErrorKind::usage,
                              "set_inputs: a key must be an input name (str), got " +
                                  py::repr(item.first).cast<std::string>());
                const auto name = item.first.cast<std::string>();
                const std::size_t i = sim.input_index(name);
                writes.emplace_back(
                    i, real_value(item.second, "set_inputs: the value for input '" + name + "'"));
              }
            } else {
              const auto all = real_array(
                  values, sim.input_count(), "set_inputs", "input (list_inputs() order)",
                  [&](std::size_t i) { return "input '" + sim.input_info(i).name + "'"; });
              for (std::size_t i = 0; i < all.size(); ++i)
                writes.emplace_back(i, all[i]);
            }
            for (const auto& [i, x] : writes)
              sim.set_input(i, x);
          },
          py::arg("values"),
          "Sets several inputs at once: a dict name -> value, or an array with one value per "
          "input in list_inputs() order. Everything is checked before anything is set.")
      .def(
          "set_state",
          [](PySimulation& s, const py::object& q, const py::object& u) {
            Simulation& sim = s.sim();
            const std::vector<double> now_q = sim.axis_positions(), now_u = sim.axis_velocities();
            const auto new_q = q.is_none() ? now_q : axis_values(s, q, now_q, "q");
            const auto new_u = u.is_none() ? now_u : axis_values(s, u, now_u, "u");
            const Simulation::Snapshot before = sim.save();
            try {
              for (std::size_t a = 0; a < new_q.size(); ++a)
                if (new_q[a] != now_q[a] || new_u[a] != now_u[a])
                  sim.set_axis_state(a, new_q[a], new_u[a]);
            } catch (const Error&) {
              sim.restore(before);  // a loop axis among others: change nothing
              throw;
            }
          },
          py::arg("q") = py::none(), py::arg("u") = py::none(),
          "Writes axis positions q and velocities u (each an array in axis_names order, or a "
          "dict axis -> value over the current ones; None keeps them). The bodies follow "
          "their joints; time does not change. A robot's free root is moved with place_body.")
      .def(
          "place_body",
          [](PySimulation& s, const py::object& body, const py::object& position,
             const py::object& rotation) {
            const int b = s.body_index(body);
            Simulation& sim = s.sim();
            Pose pose = sim.body_pose(b);
            pose.position = vec3_of(position, "place_body: position");
            if (!rotation.is_none()) pose.rotation = rotation_of(rotation);
            sim.place_body(b, pose);
          },
          py::arg("body"), py::arg("position"), py::arg("rotation") = py::none(),
          "Moves a thing or a robot's root body (by name or index; robots/<robot> is its main "
          "body) to position [m] with rotation (3x3, body to world; None keeps the current "
          "one), at rest. Time does not change.")
      .def(
          "add_thing",
          [](PySimulation& s, const std::string& shape, const py::object& size, double mass,
             const py::object& position, const py::object& rotation, const py::object& color,
             const std::string& id, bool fixed) {
            ThingSpec spec;
            if (shape == "box") {
              spec.shape = ThingShape::box;
            } else if (shape == "sphere") {
              spec.shape = ThingShape::sphere;
            } else if (shape == "cylinder") {
              spec.shape = ThingShape::cylinder;
            } else {
              throw Error(
                  ErrorKind::usage,
                  "add_thing: shape must be 'box', 'sphere' or 'cylinder', got '" + shape + "'");
            }
            const std::vector<double> sizes =
                real_array(size,
                           spec.shape == ThingShape::box      ? 3
                           : spec.shape == ThingShape::sphere ? 1
                                                              : 2,
                           "add_thing: size", "size",
                           [](std::size_t i) { return "size[" + std::to_string(i) + "]"; });
            if (spec.shape == ThingShape::box)
              spec.size_m = {sizes[0], sizes[1], sizes[2]};
            else if (spec.shape == ThingShape::sphere)
              spec.size_m = {sizes[0], sizes[0], sizes[0]};
            else
              spec.size_m = {sizes[0], sizes[0], sizes[1]};
            spec.mass_kg = mass;
            spec.pose.position = vec3_of(position, "add_thing: position");
            if (!rotation.is_none()) spec.pose.rotation = rotation_of(rotation);
            const Vec3 rgb = vec3_of(color, "add_thing: color");
            spec.rgb[0] = rgb.x;
            spec.rgb[1] = rgb.y;
            spec.rgb[2] = rgb.z;
            spec.fixed = fixed;
            return s.sim().add_thing(spec, id);
          },
          py::arg("shape"), py::arg("size"), py::arg("mass") = 1.0,
          py::arg("position") = std::vector<double>{0, 0, 0}, py::arg("rotation") = py::none(),
          py::arg("color") = std::vector<double>{0.5, 0.5, 0.5}, py::arg("id") = "",
          py::arg("fixed") = false,
          "Adds a free body at rest (SimTwo's AddThingBox/Sphere/Cylinder): shape 'box' (size: "
          "edges x, y, z), 'sphere' (size: radius) or 'cylinder' (size: radius, length along "
          "its Z), mass [kg], position [m], rotation (3x3), color (0..1); fixed=True holds it "
          "where it is put, as an obstacle. It takes one of the "
          "spare bodies (Simulation(runtime_things=N)); returns its body index. A reset removes "
          "it, a snapshot holds it.")
      .def(
          "delete_thing",
          [](PySimulation& s, const py::object& body) { s.sim().delete_thing(s.body_index(body)); },
          py::arg("body"),
          "Removes a thing (by name or index), a scene one or an added one, until a reset.")
      .def(
          "delete_obstacle", [](PySimulation& s, int index) { s.sim().delete_obstacle(index); },
          py::arg("index"),
          "Removes the scene's obstacle `index` (scene order) until a reset: it touches nothing "
          "and rays pass.")
      .def(
          "resize_body",
          [](PySimulation& s, const py::object& body, const py::object& size) {
            s.sim().resize_body(s.body_index(body), vec3_of(size, "resize_body: size"));
          },
          py::arg("body"), py::arg("size"),
          "Resizes a body's own primitive (a box: edges; a cylinder: radius, _, length; a "
          "sphere: radius, _, _), its mass as loaded, until a reset.")
      .def(
          "set_body_mass",
          [](PySimulation& s, const py::object& body, double mass, const py::object& com,
             const py::object& inertia) {
            const int b = s.body_index(body);
            Simulation::MassProperties m = s.sim().body_mass(b).with_mass(mass);
            if (!inertia.is_none()) m.inertia_kg_m2 = matrix_of(inertia, "set_body_mass: inertia");
            if (!com.is_none()) m.com_m = vec3_of(com, "set_body_mass: com");
            s.sim().set_body_mass(b, m);
          },
          py::arg("body"), py::arg("mass"), py::arg("com") = py::none(),
          py::arg("inertia") = py::none(),
          "Gives a body (by name or index) a new mass [kg] while running (SimTwo's "
          "SetSolidMass), with its centre of mass com (body frame, m) and its inertia about it "
          "(3x3, body axes, kg·m²) if given; without an inertia it scales with the mass, "
          "without com the centre stays. A jointed body's dynamics follow. A reset restores "
          "the scene's, a snapshot holds it.")
      .def(
          "body_mass",
          [](const PySimulation& s, const py::object& body) {
            const Simulation::MassProperties m = s.sim().body_mass(s.body_index(body));
            py::dict d;
            d["mass"] = m.mass_kg;
            d["com"] = vec3(m.com_m);
            d["inertia"] = mat3(m.inertia_kg_m2);
            return d;
          },
          py::arg("body"),
          "A body's mass properties as they stand: {'mass': kg, 'com': body frame (m), "
          "'inertia': about the centre of mass, body axes (kg·m²)}.")
      .def(
          "set_body_surface",
          [](PySimulation& s, const py::object& body, double mu, double mu2) {
            s.sim().set_body_surface(s.body_index(body), mu, mu2);
          },
          py::arg("body"), py::arg("mu"), py::arg("mu2") = -1.0,
          "Sets the friction of a body's own primitive (mu < 0: the scene's default) until a "
          "reset.")
      .def(
          "obstacle_present",
          [](const PySimulation& s, int index) { return s.sim().obstacle_present(index); },
          py::arg("index"))
      .def_property_readonly(
          "things",
          [](const PySimulation& s) {
            py::list out;
            for (const ThingView& v : s.sim().things()) {
              py::dict d;
              d["body"] = v.body;
              d["id"] = v.id;
              d["added"] = v.added;
              d["present"] = v.present;
              out.append(d);
            }
            return out;
          },
          "The scene's things, then the spare bodies: body index, id, added, present.");
}

}  // namespace s2sim::python
