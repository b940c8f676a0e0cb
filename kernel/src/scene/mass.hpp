#pragma once
/// \file
/// Mass properties of uniform primitives and their physical combination (massive shells).

#include <s2sim/kernel/scene.hpp>

#include <array>
#include <string>

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

/// Eigenvalues of a symmetric 3×3 matrix, ascending.
std::array<double, 3> symmetric_eigenvalues(const Mat3& a);

/// "ixx 1, iyy 2, ...": an inertia's six numbers for messages.
std::string inertia_text(const Mat3& inertia);

/// What makes a mass and an inertia about the centre of mass non-physical, empty if nothing
/// does (MuJoCo's rule): a mass >= 0 and finite, an inertia finite, symmetric, with principal
/// moments >= 0 that satisfy the triangle inequality (A + B >= C), each within a relative 1e-9.
std::string inertia_problem(double mass_kg, const Mat3& inertia);

}  // namespace s2sim::scene
