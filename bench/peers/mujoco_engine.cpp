// MuJoCo 2.2 in the peer benchmark: the MJCF files of bench/peers/mjcf, mj_step at 1 ms.
#include "engine.hpp"
#include "peer_model.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace peers {
namespace {

class MujocoEngine final : public Engine {
 public:
  explicit MujocoEngine(const SceneSpec& scene) {
    char error[1000] = "";
    model_ = mj_loadXML(scene.mjcf().c_str(), nullptr, error, sizeof error);
    if (model_ == nullptr) throw std::runtime_error(scene.mjcf().string() + ": " + error);
    data_ = mj_makeData(model_);
    switch (scene.kind) {
      case SceneSpec::Kind::robots:
        for (int i = 0; i < scene.robot_count; ++i) {
          std::string robot = "r";
          robot += std::to_string(i);
          tracked_.push_back(id(mjOBJ_BODY, robot));
          ctrl_.emplace_back(id(mjOBJ_ACTUATOR, robot + "_right"), scene.robot_volts);
          ctrl_.emplace_back(id(mjOBJ_ACTUATOR, robot + "_left"), -scene.robot_volts);
        }
        break;
      case SceneSpec::Kind::pile:
        for (int body = 1; body < model_->nbody; ++body)
          tracked_.push_back(body);
        break;
      case SceneSpec::Kind::humanoid:
      case SceneSpec::Kind::arm_loop: {
        const auto table = read_articulated(scene.ode_table());
        tracked_.push_back(id(mjOBJ_BODY, scene.kind == SceneSpec::Kind::humanoid
                                              ? table.bodies.front().name
                                              : table.bodies.back().name));
        for (const auto& h : table.hinges)
          if (h.ki_Nm_A > 0 && h.volts != 0)
            ctrl_.emplace_back(id(mjOBJ_ACTUATOR, h.name), h.volts);
        break;
      }
    }
    reset();
  }
  ~MujocoEngine() override {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  MujocoEngine(const MujocoEngine&) = delete;
  MujocoEngine& operator=(const MujocoEngine&) = delete;

  void reset() override {
    mj_resetData(model_, data_);
    for (const auto& [actuator, volts] : ctrl_)
      data_->ctrl[actuator] = volts;
    mj_forward(model_, data_);  // the bodies' poses at t = 0 (a reset leaves them unset)
  }
  void step(long steps) override {
    for (long i = 0; i < steps; ++i)
      mj_step(model_, data_);
  }
  double deepest_penetration_m() const override {
    double deepest = 0;
    for (int i = 0; i < data_->ncon; ++i)
      deepest = std::max(deepest, -data_->contact[i].dist);
    return deepest;
  }
  int tracked_count() const override { return static_cast<int>(tracked_.size()); }
  TrackedPose tracked(int index) const override {
    const int body = tracked_[static_cast<std::size_t>(index)];
    TrackedPose out;
    for (int k = 0; k < 3; ++k)
      out.position_m[static_cast<std::size_t>(k)] = data_->xpos[3 * body + k];
    const mjtNum* r = data_->xmat + 9 * body;  // row-major
    out.yaw_rad = std::atan2(r[3], r[0]);
    return out;
  }

 private:
  int id(mjtObj type, const std::string& name) const {
    const int found = mj_name2id(model_, type, name.c_str());
    if (found < 0) throw std::runtime_error("MuJoCo model has no object '" + name + "'");
    return found;
  }

  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<int> tracked_;
  std::vector<std::pair<int, double>> ctrl_;
};

}  // namespace

std::unique_ptr<Engine> make_mujoco(const SceneSpec& scene) {
  return std::make_unique<MujocoEngine>(scene);
}

}  // namespace peers
