#include "scene/primitive.hpp"
#include "scene/limits.hpp"

namespace s2sim::scene::detail {

bool PrimitiveFields::read(const Reader& r, const Element& c, bool size_radius_sets_x) {
  const std::string& n = c.name;
  if (n == "size") {
    size = r.xyz(c, size);
    size_el = &c;
    if (size_radius_sets_x) {
      size.x = r.number(c, "radius", size.x);
    } else if (r.has(c, "radius")) {
      radius = r.number(c, "radius", radius);
      radius_el = &c;
      radius_attr = "radius";
    }
  } else if (n == "radius") {
    if (r.has(c, "value")) {
      radius = r.number(c, "value", radius);
      radius_el = &c;
      radius_attr = "value";
    }
  } else if (n == "pos") {
    pos = r.xyz(c, pos);
  } else if (n == "rot_deg") {
    rot_deg = r.xyz(c, rot_deg);
  } else {
    return false;
  }
  return true;
}

void PrimitiveFields::require_positive(const Reader& r, const Element& owner, const Element* where,
                                       const char* attr, double v) {
  if (!(v > 0)) r.fail(where ? *where : owner, attr, "must be > 0, got " + format_number(v));
  // Beyond it the narrow phase (FCL/libccd) loses its precision and may not terminate.
  if (v > limits::kMaxLength_m)
    r.fail(
        where ? *where : owner, attr,
        "must be at most " + format_number(limits::kMaxLength_m) + " m, got " + format_number(v));
}

Vec3 PrimitiveFields::box_size(const Reader& r, const Element& owner) const {
  require_positive(r, owner, size_el, "x", size.x);
  require_positive(r, owner, size_el, "y", size.y);
  require_positive(r, owner, size_el, "z", size.z);
  return size;
}

}  // namespace s2sim::scene::detail
