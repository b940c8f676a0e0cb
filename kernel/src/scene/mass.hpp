#pragma once
/// \file
/// Mass properties of uniform primitives and their physical combination (massive shells).

#include <s2sim/kernel/scene.hpp>

namespace s2sim::scene {

/// Inertia of a uniform primitive of mass `mass_kg` about its centre, in its own axes
/// (cylinders along local Z: Izz = m r²/2, Ixx = Iyy = m(3r² + L²)/12).
Mat3 uniform_inertia(const Shape& shape, double mass_kg);

/// Adds a rigid part to `body` without moving the body frame: `part_com_m` is the part's
/// centre of mass and `part_inertia` its inertia about that point, both in the body frame.
/// Mass adds, the COM moves to the combined centre, inertias combine by the parallel-axis
/// theorem.
void add_rigid_part(Body& body, double part_mass_kg, const Vec3& part_com_m,
                    const Mat3& part_inertia_kg_m2);

}  // namespace s2sim::scene
