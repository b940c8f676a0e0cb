// The islands of the joint graph dealt into parts (island_plan.hpp). No Simbody here.
#include "model/island_plan.hpp"

#include "scene/joint_islands.hpp"

#include <algorithm>
#include <numeric>

namespace s2sim::model {

std::vector<PartPlan> plan_parts(const scene::Scene& scene, const Topology& topology,
                                 const std::vector<double>& axis_inertia, int parts) {
  auto whole = [&] {
    PartPlan plan;
    plan.topology = topology;
    plan.axis_inertia = axis_inertia;
    plan.global_axis.resize(topology.axes.size());
    std::iota(plan.global_axis.begin(), plan.global_axis.end(), 0);
    plan.bodies.resize(scene.bodies.size());
    std::iota(plan.bodies.begin(), plan.bodies.end(), 1);
    plan.joints.resize(scene.joints.size());
    std::iota(plan.joints.begin(), plan.joints.end(), 0);
    return std::vector<PartPlan>{std::move(plan)};
  };
  if (parts <= 1) return whole();
  // A scene-wide policy of one Simbody system that a part would not share, so that its numbers
  // would differ in the last bits: with a loop anywhere the M^-1 columns are recomputed when any
  // coordinate moves and the axis solve is one block. Such scenes keep one part, and so do
  // scenes with joint couplings (constraints too).
  if (!topology.loops.empty() || !scene.couplings.empty()) return whole();

  // Connected components over the scene bodies (the world joins nothing: robots standing on
  // the floor are separate islands).
  const std::size_t n_bodies = scene.bodies.size();
  const std::vector<int> island_root = scene::joint_island_roots(scene);

  // Islands numbered by their lowest body (their root).
  std::vector<int> island_of_body(n_bodies, -1);  // -1: loose
  std::vector<int> weight;
  std::vector<int> island_of_root(n_bodies, -1);
  std::vector<char> in_tree(n_bodies, 0);
  for (const auto& e : topology.tree)
    in_tree[static_cast<std::size_t>(e.child)] = 1;
  for (std::size_t b = 0; b < n_bodies; ++b) {
    if (!in_tree[b]) continue;
    const auto root = static_cast<std::size_t>(island_root[b]);
    if (island_of_root[root] < 0) {
      island_of_root[root] = static_cast<int>(weight.size());
      weight.push_back(0);
    }
    island_of_body[b] = island_of_root[root];
    ++weight[static_cast<std::size_t>(island_of_body[b])];
  }
  const std::size_t islands = weight.size();
  if (islands < 2) return whole();
  auto island_of_joint = [&](int j) {
    const auto& jt = scene.joints[static_cast<std::size_t>(j)];
    return island_of_body[static_cast<std::size_t>(jt.body1 >= 0 ? jt.body1 : jt.body2)];
  };
  for (const auto& axis : topology.axes)
    ++weight[static_cast<std::size_t>(island_of_joint(axis.joint))];

  // Deal: heaviest island first to the lightest part.
  std::vector<int> order(islands);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return weight[static_cast<std::size_t>(a)] > weight[static_cast<std::size_t>(b)];
  });
  const std::size_t n_parts = std::min(islands, static_cast<std::size_t>(parts));
  std::vector<long> load(n_parts, 0);
  std::vector<int> part_of_island(islands, 0);
  for (int island : order) {
    const auto lightest =
        static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    part_of_island[static_cast<std::size_t>(island)] = static_cast<int>(lightest);
    load[lightest] += weight[static_cast<std::size_t>(island)];
  }
  // The same islands in kernel order, cut into runs of about equal weight, when that is as
  // balanced: a part's bodies (and its shapes, contact wrenches and placements) then lie
  // together in the scene-wide arrays, which two threads writing at once would otherwise
  // share cache lines of at every island boundary.
  long total = 0;
  for (int w : weight)
    total += w;
  std::vector<int> run_of_island(islands, 0);
  std::vector<long> run_load(n_parts, 0);
  long before = 0;
  for (std::size_t i = 0; i < islands; ++i) {
    // The run whose share of the total holds the island's middle.
    const long middle2 = 2 * before + weight[i];  // twice the island's middle
    const auto run = std::min<long>(static_cast<long>(n_parts) - 1,
                                    middle2 * static_cast<long>(n_parts) / (2 * total));
    run_of_island[i] = static_cast<int>(run);
    run_load[static_cast<std::size_t>(run)] += weight[i];
    before += weight[i];
  }
  if (*std::max_element(run_load.begin(), run_load.end()) <=
          *std::max_element(load.begin(), load.end()) &&
      *std::min_element(run_load.begin(), run_load.end()) > 0)
    part_of_island = run_of_island;

  // A loose body (a thing, a one-solid robot) goes with the island of the jointed body nearest
  // to where it stands at load (ties: the lower body): a ball ahead of a robot is the robot's
  // part's, so that the parts' shapes stay apart and the parts can run ahead (run_ahead.cpp);
  // all in one part, the things would lie among the other part's robots.
  for (int loose : topology.loose) {
    const Vec3& at = scene.bodies[static_cast<std::size_t>(loose)].pose.position;
    double nearest = INFINITY;
    for (std::size_t b = 0; b < n_bodies; ++b) {
      if (island_of_body[b] < 0 || !in_tree[b]) continue;
      const Vec3 d = scene.bodies[b].pose.position - at;
      const double distance2 = dot(d, d);
      if (distance2 < nearest) {
        nearest = distance2;
        island_of_body[static_cast<std::size_t>(loose)] = island_of_body[b];
      }
    }
  }

  std::vector<PartPlan> plans(n_parts);
  for (auto& plan : plans)
    plan.topology.joint_is_loop = topology.joint_is_loop;
  auto part_of_body = [&](int b) -> PartPlan& {
    return plans[static_cast<std::size_t>(
        part_of_island[static_cast<std::size_t>(island_of_body[static_cast<std::size_t>(b)])])];
  };
  for (int loose : topology.loose)
    part_of_body(loose).topology.loose.push_back(loose);
  for (const auto& e : topology.tree)
    part_of_body(e.child).topology.tree.push_back(e);
  for (int j : topology.loops)
    plans[static_cast<std::size_t>(part_of_island[static_cast<std::size_t>(island_of_joint(j))])]
        .topology.loops.push_back(j);
  for (std::size_t a = 0; a < topology.axes.size(); ++a) {
    const auto& axis = topology.axes[a];
    PartPlan& plan = plans[static_cast<std::size_t>(
        part_of_island[static_cast<std::size_t>(island_of_joint(axis.joint))])];
    plan.topology.axes.push_back(axis);
    plan.axis_inertia.push_back(a < axis_inertia.size() ? axis_inertia[a] : 0.0);
    plan.global_axis.push_back(static_cast<int>(a));
  }
  for (std::size_t b = 0; b < n_bodies; ++b)
    part_of_body(static_cast<int>(b)).bodies.push_back(static_cast<int>(b) + 1);
  for (std::size_t j = 0; j < scene.joints.size(); ++j)
    plans[static_cast<std::size_t>(
              part_of_island[static_cast<std::size_t>(island_of_joint(static_cast<int>(j)))])]
        .joints.push_back(static_cast<int>(j));
  return plans;
}

}  // namespace s2sim::model
