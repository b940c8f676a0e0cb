#pragma once
/// The import tests' fixtures folder, load options, and the comparison of a model's joint
/// trajectories with MuJoCo 2.2 integrating the same file.

#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#ifdef S2SIM_TEST_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace s2sim::test {

inline const std::filesystem::path kImportFixtures =
    std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures/import";

inline SimulationOptions import_options() {
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_PLUGIN_DIR)};
  return o;
}

/// The signal of each named joint's position in the file's one robot (`robots/<r>/axes/<j>/pos`).
inline std::vector<std::size_t> joint_signals(const Simulation& sim,
                                              const std::vector<std::string>& joints) {
  std::vector<std::size_t> signals;
  const std::string robot = sim.scene().robots.at(0).id;
  for (const std::string& j : joints)
    signals.push_back(sim.signal_index("robots/" + robot + "/axes/" + j + "/pos"));
  return signals;
}

#ifdef S2SIM_TEST_HAVE_MUJOCO
/// How MuJoCo integrates: RK4 at 0.1 ms (close to the exact trajectory), or S2Sim's own law at
/// S2Sim's step (MuJoCo's semi-implicit Euler, its first velocity update a half step).
enum class MujocoIntegration { rk4_fine, s2sim_law };

struct MujocoDifference {
  double largest_rad = 1e300;  ///< of the joint positions (hinges wrapped), every 10 ms
  double swing = 0;            ///< MuJoCo's largest joint position
};

/// A constant torque (force) on a joint: its effort input in S2Sim, a generalized force in MuJoCo.
struct JointEffort {
  std::string joint;
  double value = 0;
};

/// S2Sim loading `file` at `step_s` against MuJoCo loading `mujoco_file` (the same model, or
/// the same file), contacts off in MuJoCo, over `seconds`, on the joints named.
inline MujocoDifference difference_from_mujoco(const std::filesystem::path& file,
                                               const std::filesystem::path& mujoco_file,
                                               const std::vector<std::string>& joints,
                                               double step_s, double seconds,
                                               MujocoIntegration integration,
                                               const std::vector<JointEffort>& efforts = {}) {
  MujocoDifference out;
  char error[1000] = "";
  mjModel* m = mj_loadXML(mujoco_file.string().c_str(), nullptr, error, sizeof error);
  if (!m) {
    ADD_FAILURE() << mujoco_file << ": " << error;
    return out;
  }
  const bool fine = integration == MujocoIntegration::rk4_fine;
  m->opt.integrator = fine ? mjINT_RK4 : mjINT_EULER;
  m->opt.timestep = fine ? 1e-4 : step_s;
  m->opt.disableflags |= mjDSBL_CONTACT;
  mjData* d = mj_makeData(m);
  for (const JointEffort& e : efforts) {
    const int id = mj_name2id(m, mjOBJ_JOINT, e.joint.c_str());
    EXPECT_GE(id, 0) << e.joint;
    if (id >= 0) d->qfrc_applied[m->jnt_dofadr[id]] = e.value;
  }
  if (!fine) {
    // S2Sim's first step: u = h/2 · u'(q0, 0), q = q0 + h · u; then Euler as MuJoCo's.
    mj_forward(m, d);
    mju_addToScl(d->qvel, d->qacc, 0.5 * step_s, m->nv);
    mj_integratePos(m, d->qpos, d->qvel, step_s);
    d->time += step_s;
  }
  const int mujoco_steps = static_cast<int>(std::llround(0.01 / m->opt.timestep));
  SimulationOptions o = import_options();
  o.physics_step_s = step_s;
  auto sim = Simulation::load(file, o);
  const auto ticks = static_cast<std::int64_t>(std::llround(0.01 / step_s));
  const std::vector<std::size_t> signals = joint_signals(*sim, joints);
  for (const JointEffort& e : efforts)
    sim->set_input("robots/" + sim->scene().robots.at(0).id + "/axes/" + e.joint + "/effort",
                   e.value);
  std::vector<int> qpos;
  for (const std::string& name : joints) {
    const int id = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    EXPECT_GE(id, 0) << name;
    qpos.push_back(id < 0 ? 0 : m->jnt_qposadr[id]);
  }
  out.largest_rad = 0;
  bool first = !fine;
  for (int k = 0; k < static_cast<int>(std::llround(seconds / 0.01)); ++k) {
    sim->step(ticks);
    for (int i = first ? 1 : 0; i < mujoco_steps; ++i)
      mj_step(m, d);
    first = false;
    EXPECT_EQ(sim->contact_count(), 0u) << "the model touched itself";
    for (std::size_t j = 0; j < signals.size(); ++j) {
      // S2Sim's hinge angle wraps at ±π.
      const double diff = std::remainder(sim->signal(signals[j]) - d->qpos[qpos[j]], 2 * kPi);
      out.largest_rad = std::max(out.largest_rad, std::abs(diff));
      out.swing = std::max(out.swing, std::abs(d->qpos[qpos[j]]));
    }
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}
#endif

}  // namespace s2sim::test
