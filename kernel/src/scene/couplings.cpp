// The checks a joint coupling must pass before the multibody holds it (scene.hpp,
// validate_couplings; the constraint itself: docs/models/multibody.md, "Coupled joints").
#include "scene/attributes.hpp"

#include <s2sim/kernel/scene.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace s2sim::scene {
namespace {

const char* type_name(JointType t) {
  switch (t) {
    case JointType::hinge:
      return "hinge";
    case JointType::slider:
      return "slider";
    case JointType::universal:
      return "universal";
    case JointType::ball:
      return "ball";
    case JointType::fixed:
      return "fixed";
  }
  return "?";
}

}  // namespace

void validate_couplings(const Scene& scene) {
  const int n_joints = static_cast<int>(scene.joints.size());
  std::vector<int> leader_of(static_cast<std::size_t>(n_joints), -1);
  for (const JointCoupling& c : scene.couplings) {
    auto fail = [&](const std::string& message) {
      throw Error(ErrorKind::scene, c.where, "joint coupling: " + message);
    };
    if (c.follower < 0 || c.follower >= n_joints || c.leader < 0 || c.leader >= n_joints)
      fail("joint index out of range (follower " + std::to_string(c.follower) + ", leader " +
           std::to_string(c.leader) + ")");
    const Joint& f = scene.joints[static_cast<std::size_t>(c.follower)];
    const Joint& l = scene.joints[static_cast<std::size_t>(c.leader)];
    const std::string names = "joint '" + f.id + "' following '" + l.id + "'";
    if (c.follower == c.leader) fail("joint '" + f.id + "' cannot follow itself");
    for (const Joint* j : {&f, &l})
      if (j->type != JointType::hinge && j->type != JointType::slider)
        fail(names + ": joint '" + j->id + "' is " + type_name(j->type) +
             "; only hinges and sliders can be coupled");
    if (f.robot != l.robot) fail(names + ": the two joints belong to different robots");
    if (!std::isfinite(c.multiplier) || !std::isfinite(c.offset))
      fail(names + ": multiplier " + format_number(c.multiplier) + " and offset " +
           format_number(c.offset) + " must be finite");
    int& leader = leader_of[static_cast<std::size_t>(c.follower)];
    if (leader >= 0)
      fail("joint '" + f.id + "' already follows '" +
           scene.joints[static_cast<std::size_t>(leader)].id + "'; it cannot also follow '" + l.id +
           "'");
    leader = c.leader;
  }
  // A cycle: following the leaders from any joint comes back to it.
  for (const JointCoupling& c : scene.couplings) {
    int j = c.leader;
    for (int steps = 0; j >= 0 && steps <= n_joints; ++steps) {
      if (j == c.follower)
        throw Error(ErrorKind::scene, c.where,
                    "joint coupling: joint '" + scene.joints[static_cast<std::size_t>(j)].id +
                        "' follows itself through a cycle of couplings");
      j = leader_of[static_cast<std::size_t>(j)];
    }
  }
}

}  // namespace s2sim::scene
