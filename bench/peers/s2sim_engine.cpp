// S2Sim in the peer benchmark: the public façade (s2sim::Simulation) on the repository's scenes.
#include "engine.hpp"
#include "peer_model.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <algorithm>
#include <cmath>
#include <thread>
#include <utility>

namespace peers {
namespace {

class S2SimEngine final : public Engine {
 public:
  S2SimEngine(const SceneSpec& scene, int threads, bool simbody_dynamics_only = false,
              bool run_ahead = true) {
    s2sim::SimulationOptions options;
    options.threads = threads;      // s2sim-par2: the islands on two threads
    options.run_ahead = run_ahead;  // s2sim-par2-lockstep: the parts tick by tick
    options.simbody_dynamics_only = simbody_dynamics_only;  // s2sim-simbody: no fast path
    // No substeps in any engine: scenes/pile asks for two, the benchmark compares at 1 ms.
    options.physics_step_s = 0.001;
    options.substeps = 1;
    sim_ = s2sim::Simulation::load(scene.s2sim_scene(), options);
    const auto& sc = sim_->scene();
    switch (scene.kind) {
      case SceneSpec::Kind::robots:
        for (const auto& robot : sc.robots) {
          tracked_.push_back(robot.main_body + 1);
          voltages_.emplace_back(
              sim_->input_index("robots/" + robot.id + "/axes/right/ref_voltage"),
              scene.robot_volts);
          voltages_.emplace_back(sim_->input_index("robots/" + robot.id + "/axes/left/ref_voltage"),
                                 -scene.robot_volts);
        }
        break;
      case SceneSpec::Kind::pile:
        for (int thing : sc.things)
          tracked_.push_back(thing + 1);
        break;
      case SceneSpec::Kind::humanoid:
      case SceneSpec::Kind::arm_loop: {
        const auto model = read_articulated(scene.ode_table());
        const auto& robot = sc.robots.at(0);
        // The humanoid's pelvis (its first body), the arm's coupler (its last).
        const int tracked_body = scene.kind == SceneSpec::Kind::humanoid
                                     ? robot.bodies.front()
                                     : robot.bodies.at(model.bodies.size() - 1);
        tracked_.push_back(tracked_body + 1);
        for (const auto& h : model.hinges)
          if (h.ki_Nm_A > 0 && h.volts != 0)
            voltages_.emplace_back(
                sim_->input_index("robots/" + robot.id + "/axes/" + h.name + "/ref_voltage"),
                h.volts);
        break;
      }
    }
    apply_voltages();
  }

  void reset() override {
    sim_->reset();
    apply_voltages();
  }
  void step(long steps) override { sim_->step(steps); }

  double deepest_penetration_m() const override {
    double deepest = 0;
    for (std::size_t i = 0; i < sim_->contact_count(); ++i)
      deepest = std::max(deepest, sim_->contact(i).depth_m);
    return deepest;
  }

  int tracked_count() const override { return static_cast<int>(tracked_.size()); }
  TrackedPose tracked(int index) const override {
    const s2sim::Pose& pose = sim_->body_pose(tracked_[static_cast<std::size_t>(index)]);
    TrackedPose out;
    out.position_m = {pose.position.x, pose.position.y, pose.position.z};
    out.yaw_rad = std::atan2(pose.rotation.m[1][0], pose.rotation.m[0][0]);
    return out;
  }

 private:
  void apply_voltages() {
    for (const auto& [input, volts] : voltages_)
      sim_->set_input(input, volts);
  }

  std::unique_ptr<s2sim::Simulation> sim_;
  std::vector<int> tracked_;
  std::vector<std::pair<std::size_t, double>> voltages_;
};

/// Two serial copies of the scene stepped at once, one per thread, each its own Simulation:
/// nothing shared, nothing waited for until both are done. What the machine gives two threads
/// on this very work, measured beside s2sim-par2 in the same rounds: the ceiling of any
/// parallel stepping of the scene on two threads (a host that shares or slows its vCPUs when
/// both are busy lowers it, and s2sim-par2 with it).
class S2SimCopiesEngine final : public Engine {
 public:
  explicit S2SimCopiesEngine(const SceneSpec& scene) : first_(scene, 1), second_(scene, 1) {}
  void reset() override {
    first_.reset();
    second_.reset();
  }
  void step(long steps) override {
    std::thread other([&] { second_.step(steps); });
    first_.step(steps);
    other.join();
  }
  double deepest_penetration_m() const override { return first_.deepest_penetration_m(); }
  int tracked_count() const override { return first_.tracked_count(); }
  TrackedPose tracked(int index) const override { return first_.tracked(index); }

 private:
  S2SimEngine first_, second_;
};

}  // namespace

std::unique_ptr<Engine> make_s2sim(const SceneSpec& scene) {
  return std::make_unique<S2SimEngine>(scene, 1);
}

std::unique_ptr<Engine> make_s2sim_par2(const SceneSpec& scene) {
  return std::make_unique<S2SimEngine>(scene, 2);
}

std::unique_ptr<Engine> make_s2sim_par2_lockstep(const SceneSpec& scene) {
  return std::make_unique<S2SimEngine>(scene, 2, false, false);
}

std::unique_ptr<Engine> make_s2sim_simbody(const SceneSpec& scene) {
  return std::make_unique<S2SimEngine>(scene, 1, true);
}

std::unique_ptr<Engine> make_s2sim_copies2(const SceneSpec& scene) {
  return std::make_unique<S2SimCopiesEngine>(scene);
}

}  // namespace peers
