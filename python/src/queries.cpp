// What touches and what a ray meets, as NumPy arrays: the contacts of the last substep and ray
// casts against every collision surface (Simulation::contact, Simulation::cast_ray).
#include "py_simulation.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace py = pybind11;

namespace s2sim::python {

namespace {

void put(py::array_t<double>& rows, py::ssize_t i, const Vec3& v) {
  auto w = rows.mutable_unchecked<2>();
  w(i, 0) = v.x;
  w(i, 1) = v.y;
  w(i, 2) = v.z;
}

/// Rays' origins or directions: shape (3,) (one ray) or (n, 3), real, finite; `rays` is the
/// count so far (-1: not known yet).
py::array_t<double> ray_rows(const py::handle& given, const char* what, py::ssize_t& rays) {
  py::array array = py::array::ensure(given);
  if (!array)
    throw Error(ErrorKind::usage, std::string("cast_rays: ") + what +
                                      " must be an array of shape (3,) or (n, 3), got " +
                                      py::repr(given).cast<std::string>());
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw Error(ErrorKind::usage, std::string("cast_rays: ") + what +
                                      "'s dtype must be a real number type, got " +
                                      py::str(array.dtype()).cast<std::string>());
  auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (rows.ndim() == 1 && rows.shape(0) == 3) rows = rows.reshape({1, 3});
  if (rows.ndim() != 2 || rows.shape(1) != 3)
    throw Error(ErrorKind::usage, std::string("cast_rays: ") + what +
                                      " must have shape (3,) or (n, 3), got shape " +
                                      py::str(array.attr("shape")).cast<std::string>());
  const auto r = rows.unchecked<2>();
  for (py::ssize_t i = 0; i < rows.shape(0); ++i)
    for (py::ssize_t k = 0; k < 3; ++k)
      if (!std::isfinite(r(i, k)))
        throw Error(ErrorKind::usage, std::string("cast_rays: ") + what + "[" + std::to_string(i) +
                                          "] is not finite");
  if (rays < 0 || rays == 1)
    rays = std::max(rays, rows.shape(0));
  else if (rows.shape(0) != 1 && rows.shape(0) != rays)
    throw Error(ErrorKind::usage,
                "cast_rays: origins and directions must have as many rows "
                "(or one of them one), got " +
                    std::to_string(rays) + " and " + std::to_string(rows.shape(0)));
  return rows;
}

py::dict cast_rays(const PySimulation& s, const py::handle& origins, const py::handle& directions,
                   double max_distance_m, const py::object& ignore) {
  if (!std::isfinite(max_distance_m) || max_distance_m <= 0)
    throw Error(ErrorKind::usage, "cast_rays: max_distance must be finite and > 0 m, got " +
                                      std::to_string(max_distance_m));
  const int ignore_body = ignore.is_none() ? -1 : s.body_index(ignore);
  py::ssize_t rays = -1;
  const auto from = ray_rows(origins, "origins", rays);
  const auto along = ray_rows(directions, "directions", rays);
  const Simulation& sim = s.sim();
  py::array_t<bool> hit(rays);
  py::array_t<double> distance(rays);
  py::array_t<double> point({rays, py::ssize_t{3}}), normal({rays, py::ssize_t{3}});
  py::array_t<int> body(rays);
  const auto o = from.unchecked<2>();
  const auto d = along.unchecked<2>();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (py::ssize_t i = 0; i < rays; ++i) {
    const py::ssize_t io = from.shape(0) == 1 ? 0 : i, id = along.shape(0) == 1 ? 0 : i;
    const Vec3 origin{o(io, 0), o(io, 1), o(io, 2)};
    const Vec3 direction{d(id, 0), d(id, 1), d(id, 2)};
    if (norm(direction) == 0)
      throw Error(ErrorKind::usage,
                  "cast_rays: directions[" + std::to_string(id) + "] is the zero vector");
    const RayHit h = sim.cast_ray(origin, direction, max_distance_m, ignore_body);
    hit.mutable_at(i) = h.hit;
    distance.mutable_at(i) = h.hit ? h.distance_m : std::numeric_limits<double>::infinity();
    put(point, i, h.hit ? h.point_m : Vec3{nan, nan, nan});
    put(normal, i, h.hit ? h.normal : Vec3{nan, nan, nan});
    body.mutable_at(i) = h.hit ? static_cast<int>(h.body.index) : -1;
  }
  py::dict out;
  out["hit"] = hit;
  out["distance"] = distance;
  out["point"] = point;
  out["normal"] = normal;
  out["body"] = body;
  return out;
}

}  // namespace

void bind_queries(PySimulationClass& cls) {
  cls.def_property_readonly(
         "contact_count", [](const PySimulation& s) { return s.sim().contact_count(); },
         "Contact points of the last physics substep.")
      .def(
          "contacts",
          [](const PySimulation& s) {
            const Simulation& sim = s.sim();
            const auto n = static_cast<py::ssize_t>(sim.contact_count());
            py::array_t<int> body_a(n), body_b(n);
            py::array_t<double> point({n, py::ssize_t{3}}), normal({n, py::ssize_t{3}}),
                force({n, py::ssize_t{3}}), depth(n);
            for (py::ssize_t i = 0; i < n; ++i) {
              const ContactInfo& c = sim.contact(static_cast<std::size_t>(i));
              body_a.mutable_at(i) = static_cast<int>(c.body_a.index);
              body_b.mutable_at(i) = static_cast<int>(c.body_b.index);
              put(point, i, c.point_m);
              put(normal, i, c.normal);
              put(force, i, c.force_N);
              depth.mutable_at(i) = c.depth_m;
            }
            py::dict out;
            out["body_a"] = body_a;
            out["body_b"] = body_b;
            out["point"] = point;
            out["normal"] = normal;
            out["force"] = force;
            out["depth"] = depth;
            return out;
          },
          "The contacts of the last physics substep, as a dict of arrays (copies: the count "
          "changes every substep), one row per contact point: body_a (a moving body's index "
          "into body_names), body_b (the other; 0 for the ground, a wall or an obstacle), "
          "point [m] (world, on body_a's surface), normal (unit, from body_b toward body_a), "
          "force [N] (on body_a; body_b gets the opposite), depth [m].")
      .def("cast_rays", &cast_rays, py::arg("origins"), py::arg("directions"),
           py::arg("max_distance"), py::arg("ignore_body") = py::none(),
           "The first collision surface along each ray (what sensors see: ground, walls, "
           "obstacles, every body). origins and directions: shape (3,) or (n, 3), world frame "
           "(directions need not be unit); max_distance [m]; ignore_body: a body (name or "
           "index) whose surfaces are skipped. Returns a dict of arrays: hit (bool), distance "
           "[m] (inf on a miss), point and normal (NaN on a miss), body (index, -1 on a miss).")
      .def(
          "cast_ray",
          [](const PySimulation& s, const py::object& origin, const py::object& direction,
             double max_distance_m, const py::object& ignore) -> py::object {
            py::dict rays = cast_rays(s, origin, direction, max_distance_m, ignore);
            if (py::len(rays["hit"]) != 1)
              throw Error(ErrorKind::usage,
                          "cast_ray: one origin and one direction of shape (3,); use "
                          "cast_rays for several");
            if (!rays["hit"].attr("__getitem__")(0).cast<bool>()) return py::none();
            py::dict hit;
            hit["distance"] = rays["distance"].attr("__getitem__")(0).cast<double>();
            hit["point"] = rays["point"].attr("__getitem__")(0);
            hit["normal"] = rays["normal"].attr("__getitem__")(0);
            const int b = rays["body"].attr("__getitem__")(0).cast<int>();
            hit["body"] = b;
            hit["body_name"] = s.body_names().at(static_cast<std::size_t>(b));
            return hit;
          },
          py::arg("origin"), py::arg("direction"), py::arg("max_distance"),
          py::arg("ignore_body") = py::none(),
          "One ray (cast_rays): None on a miss, else a dict distance [m], point, normal, body "
          "(index) and body_name.");
}

}  // namespace s2sim::python
