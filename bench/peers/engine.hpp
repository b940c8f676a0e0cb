#pragma once
// The peer benchmark's view of a physics engine (bench/peers, docs/benchmarks.md): S2Sim
// through its façade, MuJoCo and ODE through their C APIs, Bullet and DART through their C++
// ones, each loaded with the same scene.

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace peers {

/// Which scene to build, and where the repository's copies of it are.
struct SceneSpec {
  enum class Kind { robots, pile, humanoid, arm_loop };
  std::string name;  ///< as reported: robots_16, pile, ...
  Kind kind = Kind::robots;
  int robot_count = 1;
  double robot_volts = 6.0;          ///< right wheel +V, left −V: straight ahead
  std::filesystem::path source_dir;  ///< the repository root
  /// S2Sim's scene folder, the MJCF file and (articulated scenes) the ODE table.
  std::filesystem::path s2sim_scene() const;
  std::filesystem::path mjcf() const;
  std::filesystem::path ode_table() const;
};

/// Pose of a tracked body: position (m) and heading (yaw about world Z, rad).
struct TrackedPose {
  std::array<double, 3> position_m{};
  double yaw_rad = 0;
};

/// One engine loaded with one scene. step() is what the driver times; the rest is read outside
/// the timed section.
class Engine {
 public:
  virtual ~Engine() = default;
  /// Back to the initial state with the scene's voltages applied.
  virtual void reset() = 0;
  /// Advances `steps` steps of 1 ms.
  virtual void step(long steps) = 0;
  /// The deepest penetration (m) among the contacts of the last step, 0 without contact.
  virtual double deepest_penetration_m() const = 0;
  /// The bodies the outcome follows: robot chassis, pile bodies, the humanoid's pelvis, the
  /// arm's coupler.
  virtual int tracked_count() const = 0;
  virtual TrackedPose tracked(int index) const = 0;
};

/// An engine variant the driver runs: its name and how to build it for a scene (nullptr when
/// it cannot).
struct EngineFactory {
  std::string name;
  std::unique_ptr<Engine> (*make)(const SceneSpec& scene);
};

/// The engines built into this binary, S2Sim first.
std::vector<EngineFactory> available_engines();

std::unique_ptr<Engine> make_s2sim(const SceneSpec& scene);
/// S2Sim with SimulationOptions::threads = 2 (the islands stepped in parallel; wall time is
/// its measure, its thread CPU time is only the calling thread's).
std::unique_ptr<Engine> make_s2sim_par2(const SceneSpec& scene);
/// s2sim-par2 without running ahead (SimulationOptions::run_ahead = false): the parts wait for
/// each other and the calling thread at every tick (what running ahead gains, in the same run).
std::unique_ptr<Engine> make_s2sim_par2_lockstep(const SceneSpec& scene);
/// Two serial S2Sim copies of the scene at once, one per thread (s2sim_engine.cpp): its speed-up
/// column is twice the serial run's wall time over its own, the machine's two-thread ceiling
/// on the scene's work; its thread CPU time is one copy's.
std::unique_ptr<Engine> make_s2sim_copies2(const SceneSpec& scene);
/// S2Sim with SimulationOptions::simbody_dynamics_only: Simbody's realize chain where the
/// small-tree fast path would run (what the fast path gains, in the same run).
std::unique_ptr<Engine> make_s2sim_simbody(const SceneSpec& scene);
#ifdef S2SIM_PEERS_HAVE_MUJOCO
std::unique_ptr<Engine> make_mujoco(const SceneSpec& scene);
#endif
#ifdef S2SIM_PEERS_HAVE_BULLET
/// Bullet's btMultiBody for the jointed scenes, rigid bodies for the pile (bullet_engine.cpp).
std::unique_ptr<Engine> make_bullet(const SceneSpec& scene);
#endif
#ifdef S2SIM_PEERS_HAVE_DART
/// DART's World with its default solver and DART's ODE collision detector; the arm's loop a
/// ball joint constraint (dart_engine.cpp).
std::unique_ptr<Engine> make_dart(const SceneSpec& scene);
/// The same on DART's default collision detector, FCL, as DART sets it up (meshed primitives).
std::unique_ptr<Engine> make_dart_fcl(const SceneSpec& scene);
#endif
#ifdef S2SIM_PEERS_HAVE_ODE
std::unique_ptr<Engine> make_ode_quickstep(const SceneSpec& scene);
std::unique_ptr<Engine> make_ode_worldstep(const SceneSpec& scene);
#endif

}  // namespace peers
