/// \file
/// Joints of several degrees of freedom as one-axis joints in series (docs/models/import.md,
/// "Joints"): MJCF's several joints in one body, URDF's planar joint, SDF's universal and
/// revolute2. Between each two joints of a series is a massless link at the child's frame.

#include "scene/import_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace s2sim::scene::detail {
namespace {

bool link_named(const ImportedModel& model, const std::string& name) {
  return std::any_of(model.links.begin(), model.links.end(),
                     [&](const ImportedLink& l) { return l.name == name; });
}

bool joint_named(const ImportedModel& model, const std::string& name) {
  return std::any_of(model.joints.begin(), model.joints.end(),
                     [&](const ImportedJoint& j) { return j.name == name; });
}

/// `wanted`, or with `_2`, `_3`... after it when the model already has that name.
template <class Taken>
std::string unique_name(const std::string& wanted, Taken taken) {
  if (!taken(wanted)) return wanted;
  for (int k = 2;; ++k) {
    const std::string candidate = wanted + "_" + std::to_string(k);
    if (!taken(candidate)) return candidate;
  }
}

/// The joint's motions at the start pose, as twists about the model origin (ω, v): a hinge
/// turns about its axis through its anchor, a slider moves along its axis, a ball turns about
/// three axes through its anchor.
void add_twists(const ImportedJoint& j, std::vector<std::array<double, 6>>& twists) {
  auto hinge = [&](const Vec3& a) {
    const Vec3 v = cross(j.anchor_m, a);
    twists.push_back({a.x, a.y, a.z, v.x, v.y, v.z});
  };
  switch (j.type) {
    case ImportedJointType::prismatic:
      twists.push_back({0, 0, 0, j.axis.x, j.axis.y, j.axis.z});
      break;
    case ImportedJointType::ball:
      hinge(Vec3{1, 0, 0});
      hinge(Vec3{0, 1, 0});
      hinge(Vec3{0, 0, 1});
      break;
    case ImportedJointType::floating:
      for (int k = 0; k < 6; ++k) {
        std::array<double, 6> t{};
        t[static_cast<std::size_t>(k)] = 1;
        twists.push_back(t);
      }
      break;
    case ImportedJointType::fixed:
      break;
    default:
      hinge(j.axis);
      break;
  }
}

/// Joints in series with a massless link between them must move the child in independent
/// ways, or the mass matrix is singular: a Gram-Schmidt pass over their twists.
void check_independent(const std::vector<ImportedJoint>& joints, const std::string& child) {
  std::vector<std::array<double, 6>> basis;
  for (const ImportedJoint& j : joints) {
    std::vector<std::array<double, 6>> twists;
    add_twists(j, twists);
    for (std::array<double, 6> t : twists) {
      double size = 0;
      for (double c : t)
        size += c * c;
      for (const auto& b : basis) {
        double along = 0;
        for (std::size_t k = 0; k < 6; ++k)
          along += t[k] * b[k];
        for (std::size_t k = 0; k < 6; ++k)
          t[k] -= along * b[k];
      }
      double left = 0;
      for (double c : t)
        left += c * c;
      if (!(left > 1e-18 * std::max(1.0, size)))
        throw Error(ErrorKind::scene, j.where,
                    "joint '" + j.name + "' moves link '" + child +
                        "' in a way the joints before it in the same body already do (parallel "
                        "axes through one line, or a repeated motion): its mass matrix would be "
                        "singular");
      const double n = std::sqrt(left);
      for (double& c : t)
        c /= n;
      basis.push_back(t);
    }
  }
}

}  // namespace

void add_joints_in_series(ImportedModel& model, std::vector<ImportedJoint> joints) {
  if (joints.empty()) return;
  const int parent = joints.front().parent;
  const int child = joints.front().child;
  check_independent(joints, model.links[static_cast<std::size_t>(child)].name);
  for (std::size_t k = 0; k < joints.size(); ++k) {
    ImportedJoint& j = joints[k];
    j.name = unique_name(j.name, [&](const std::string& n) { return joint_named(model, n); });
    j.parent = parent;
    j.child = child;
    if (k > 0) j.parent = static_cast<int>(model.links.size() - 1);
    if (k + 1 < joints.size()) {
      // The link this joint moves and the next one carries: massless, at the child's frame.
      const ImportedLink& end = model.links[static_cast<std::size_t>(child)];
      ImportedLink between;
      between.name = unique_name(end.name + "." + j.name,
                                 [&](const std::string& n) { return link_named(model, n); });
      between.pose = end.pose;
      between.where = j.where;
      between.inertia_where = j.where;
      model.links.push_back(std::move(between));
      j.child = static_cast<int>(model.links.size() - 1);
    }
    model.joints.push_back(std::move(j));
  }
}

std::vector<ImportedJoint> planar_joints(const ImportedJoint& planar, const Vec3& in_plane_x) {
  const Vec3 normal = planar.axis;
  Vec3 x = in_plane_x - dot(in_plane_x, normal) * normal;
  if (!(norm(x) > 1e-6)) {  // the frame's x along the normal: its y, or the model's y
    const Vec3 other = std::abs(normal.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
    x = other - dot(other, normal) * normal;
  }
  x = x / norm(x);
  const Vec3 y = cross(normal, x);
  std::vector<ImportedJoint> joints(3, planar);
  const char* suffixes[] = {"_x", "_y", "_rot"};
  const Vec3 axes[] = {x, y, normal};
  for (std::size_t k = 0; k < 3; ++k) {
    joints[k].name = planar.name + suffixes[k];
    joints[k].axis = axes[k];
    joints[k].type = k < 2 ? ImportedJointType::prismatic : ImportedJointType::continuous;
    joints[k].limited = false;
  }
  return joints;
}

}  // namespace s2sim::scene::detail
