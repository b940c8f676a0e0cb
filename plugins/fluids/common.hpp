#pragma once
/// \file
/// What the three fluid components share: the `semantics` switch, located errors, per-axis
/// parameters (docs/models/fluids.md, docs/plugins.md "fluids").

#include <s2sim/sdk.hpp>

#include <string>
#include <string_view>

namespace s2sim::fluids {

/// Whether the element asks for SimTwo's form (`semantics='simtwo'`, set by the kernel on
/// the components it makes for a SimTwo solid) rather than the physical one (the default).
inline bool simtwo_semantics(const Params& p) {
  return p.choice("semantics", {"s2sim", "simtwo"}, "s2sim") == "simtwo";
}

/// A scene error located at the attribute `path` of the component's element.
inline Error bad_value(const Params& p, std::string_view path, const std::string& message) {
  return Error(ErrorKind::scene, p.where(path), message);
}

/// A per-axis parameter: `<name>_x`, `<name>_y`, `<name>_z`, each defaulting to `<name>`, which
/// defaults to `fallback`; every value must be in `range`.
inline Vec3 per_axis(const Params& p, const std::string& name, double fallback, Range range) {
  const double all = p.number(name, fallback, range);
  return {p.number(name + "_x", all, range), p.number(name + "_y", all, range),
          p.number(name + "_z", all, range)};
}

/// `v` expressed in the frame whose rotation (to world) is `r`.
inline Vec3 to_local(const Mat3& r, const Vec3& v) {
  return r.transposed() * v;
}

/// Componentwise product.
inline Vec3 times(const Vec3& a, const Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}

/// Componentwise v·|v|.
inline Vec3 signed_square(const Vec3& v) {
  return {v.x * std::abs(v.x), v.y * std::abs(v.y), v.z * std::abs(v.z)};
}

}  // namespace s2sim::fluids
