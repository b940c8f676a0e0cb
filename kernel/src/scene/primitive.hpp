#pragma once
/// \file
/// The geometry children every SimTwo primitive shares (`<size>`, `<radius>`, `<pos>`,
/// `<rot_deg>`), read once for solids, shells and obstacles, with the elements that set them
/// so that a bad value is reported where it was written.

#include "scene/attributes.hpp"

#include <s2sim/math.hpp>

namespace s2sim::scene::detail {

struct PrimitiveFields {
  Vec3 size{1, 1, 1};
  const Element* size_el = nullptr;
  /// SimTwo keeps one radius variable, set by `<size radius>` and `<radius value>` in order.
  double radius = 1;
  const Element* radius_el = nullptr;
  const char* radius_attr = "radius";
  Vec3 pos, rot_deg;

  /// Reads `c` when it is `<size>`, `<radius>`, `<pos>` or `<rot_deg>`; returns whether it was.
  /// `size_radius_sets_x`: obstacles read `<size radius>` into size x (§5), solids and shells
  /// into the radius.
  bool read(const Reader& r, const Element& c, bool size_radius_sets_x = false);

  /// Throws, located at `where` (or `owner` when nothing set the value), unless v > 0.
  static void require_positive(const Reader& r, const Element& owner, const Element* where,
                               const char* attr, double v);
  /// The box edges, each required positive.
  Vec3 box_size(const Reader& r, const Element& owner) const;
};

}  // namespace s2sim::scene::detail
