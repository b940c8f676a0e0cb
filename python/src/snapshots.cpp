// Snapshot's pickling and its construction from parts (what s2sim/snapshots.py writes to and
// reads from a file): the layout id, the segments and the values, bit for bit.
#include "py_simulation.hpp"

#include <pybind11/stl.h>

#include <cstring>
#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;

namespace s2sim::python {

namespace {

/// The pickled form's version: a change of the tuple below gets a new one.
constexpr int kPickleVersion = 1;

using SegmentTuple = std::tuple<std::string, std::size_t, std::size_t>;

std::vector<SegmentTuple> segments_of(const PySnapshot& s) {
  std::vector<SegmentTuple> out;
  for (const auto& seg : s.snapshot.segments)
    out.emplace_back(seg.name, seg.size, seg.unit);
  return out;
}

PySnapshot from_parts(std::uint64_t layout, const std::vector<SegmentTuple>& segments,
                      const py::bytes& values, double time_s) {
  PySnapshot s;
  s.snapshot.layout = layout;
  s.time_s = time_s;
  for (const auto& [name, size, unit] : segments) {
    if (unit == 0) throw Error(ErrorKind::usage, "snapshot: segment '" + name + "' has unit 0");
    s.snapshot.segments.push_back({name, size, unit});
  }
  const std::string bytes = values;
  if (bytes.size() % sizeof(double) != 0)
    throw Error(ErrorKind::usage, "snapshot: the values are " + std::to_string(bytes.size()) +
                                      " bytes, not a whole number of float64");
  s.snapshot.values.resize(bytes.size() / sizeof(double));
  if (!bytes.empty()) std::memcpy(s.snapshot.values.data(), bytes.data(), bytes.size());
  return s;
}

py::bytes bytes_of(const PySnapshot& s) {
  return {reinterpret_cast<const char*>(s.snapshot.values.data()),
          s.snapshot.values.size() * sizeof(double)};
}

}  // namespace

void bind_snapshot(py::class_<PySnapshot>& cls) {
  cls.def(py::pickle(
              [](const PySnapshot& s) {
                return py::make_tuple(kPickleVersion, s.snapshot.layout, segments_of(s),
                                      bytes_of(s), s.time_s);
              },
              [](const py::tuple& t) {
                if (t.size() != 5 || t[0].cast<int>() != kPickleVersion)
                  throw Error(ErrorKind::usage,
                              "snapshot: a pickle of another version (this one reads version " +
                                  std::to_string(kPickleVersion) + ")");
                return from_parts(t[1].cast<std::uint64_t>(),
                                  t[2].cast<std::vector<SegmentTuple>>(), t[3].cast<py::bytes>(),
                                  t[4].cast<double>());
              }))
      .def_static("_from_parts", &from_parts, py::arg("layout"), py::arg("segments"),
                  py::arg("values"), py::arg("time"),
                  "A snapshot from what save_snapshot wrote (s2sim/snapshots.py).")
      .def_property_readonly("segments", &segments_of,
                             "The layout: (name, size, unit) per segment, in order.")
      .def_property_readonly("value_bytes", &bytes_of,
                             "The values as bytes (float64, the machine's byte order).")
      .def("__eq__", [](const PySnapshot& a, const PySnapshot& b) {
        return a.snapshot.layout == b.snapshot.layout && a.time_s == b.time_s &&
               segments_of(a) == segments_of(b) &&
               a.snapshot.values.size() == b.snapshot.values.size() &&
               std::memcmp(a.snapshot.values.data(), b.snapshot.values.data(),
                           a.snapshot.values.size() * sizeof(double)) == 0;  // bit for bit
      });
}

}  // namespace s2sim::python
