#pragma once
/// \file
/// The `pascal_script` controller (docs/scripting.md): the model it resolves at load (SimTwo's
/// index tables), the compiled script it calls, and the host functions the script calls back.
/// script_controller.cpp: load, schedule, calls and errors; host_calls.cpp: the host functions.
#include "canvas_painter.hpp"
#include "compiler.hpp"
#include "host_ids.hpp"
#include "io_ports.hpp"
#include "modbus_server.hpp"
#include "script_library.hpp"
#include "sheet.hpp"

#include <s2sim/sdk.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::pascal {

inline constexpr int kMaxNumbers = 4096;
// SimTwo's trails and chart series by index; the viewer gets series chart * 100 + series.
inline constexpr int kMaxTrails = 255;
inline constexpr int kMaxCharts = 100;
/// TMotorPars's fields in record order, as AxisRef::motor holds their inputs.
enum MotorPar : int {
  kMotorRi,
  kMotorLi,
  kMotorKi,
  kMotorVmax,
  kMotorImax,
  kMotorGearRatio,
  kMotorSimple,
  kMotorActive,
  kMotorParCount
};
inline constexpr const char* kMotorParNames[kMotorParCount] = {
    "Ri", "Li", "Ki", "Vmax", "Imax", "GearRatio", "simple", "active"};
inline constexpr int kMaxChartSeries = 100;
/// The nodes a trail keeps (the viewer's too).
inline constexpr std::size_t kMaxTrailNodes = 10000;

/// Virtual-key codes the viewer can press: the input `keyboard/<code>` is 1 while held.
inline constexpr int kKeyCodes[] = {9, 13, 27, 32, 33, 34, 37, 38, 39, 40};

/// SimTwo's message for a bad index: "List index (n) out of bounds".
std::string index_error(double n);
/// A number as a script error shows it (NaN by name, 15 digits).
std::string number_text(double v);

struct AxisRef {
  std::string path;   // empty for a Fixed or Ball joint (SimTwo gives it an index too)
  std::string joint;  // the joint's ID (GetAxisIndex)
  AxisHandle axis;
  bool linear = false;
  InputHandle ref_voltage, ref_speed, ref_pos, ref_torque, controller_active;
  SignalHandle encoder{-1}, current{-1}, voltage{-1}, power{-1};  // power: V·I (GetAxisUIPower)
  SignalReader torque;  // the kernel's axis torque (GetAxisTorque)
  /// The DC motor's run-time parameters (TMotorPars order: Ri, Li, Ki, Vmax, Imax,
  /// GearRatio, simple, active); index -1 without a motor.
  std::array<InputHandle, 8> motor{};
  bool has_motor = false;
  /// The drive train's spring, friction and controller inputs (SetAxisSpring, SetFrictionDef,
  /// SetMotorControllerPars/Mode) and its energy meter (GetAxisEnergy).
  InputHandle spring_k, spring_zeropos, friction_bv, friction_fc;
  std::array<InputHandle, 5> controller{};  // kp, ki, kd, kf, mode
  SignalHandle energy_drawn{-1};
  int index = 0;  // among every robot's axes (the script state's per-axis slots)
};

struct SensorRef {
  std::string id, kind, prefix;
  SignalHandle value{-1};
  std::vector<SignalHandle> rays;  // a ranger's rays; empty otherwise
  InputHandle vin{-1};
};

/// A solid's or thing's look and mass as loaded (GetSolidColor, GetSolidSize, GetSolidMass...).
struct Look {
  double rgba_loaded[4] = {0, 0, 0, 0};
  double rgba[4] = {0, 0, 0, 0};  // as the script last set it (a reset restores the loaded)
  Vec3 size;                      // SimTwo's GetSize: box edges; cylinder r, r, l; sphere r, r, r
  Vec3 com;                       // centre of mass in the body frame
  int round = 0;                  // its primitive: 0 a box (or hull), 1 a cylinder, 2 a sphere
};

struct SolidRef {
  std::string id;
  BodyHandle body;
  Look look;
  std::string tag;     // SetSolidTag's
  InputHandle belt{};  // a conveyor belt's surface speed (index -1 for other solids)
  int canvas = -1;     // its canvas in ScriptController::canvases_, -1 for none
};

struct RobotRef {
  std::string id;
  BodyHandle main;
  Vec3 origin, offset;
  double yaw = 0;
  Pose main_load_pose;  // read at the first initialize()
  std::vector<SolidRef> solids;
  std::vector<AxisRef> axes;
  std::vector<int> sensors;  // indices into global sensors
  std::vector<std::string> shell_tags;
  struct Shell {
    BodyHandle body;
    int geom = 1;   // its index in the body's geoms (0 is the solid's own)
    Vec3 position;  // in the body frame
    double rgba[4] = {0, 0, 0, 0};
  };
  std::vector<Shell> shells;  // in SimTwo's order
};

struct ThingRef {
  std::string id;
  BodyHandle body;
  Look look;
};

struct ObstacleRef {
  std::string id;
  Vec3 position;  // a scene obstacle's; an added one's is its body's
  Mat3 rotation;
  double rgba[4] = {0, 0, 0, 0};
  int scene_index = -1;  // in the scene's obstacles; -1 for one added while running
  BodyHandle body;       // the spare body an added obstacle holds
  int canvas = -1;       // its canvas in ScriptController::canvases_, -1 for none
};

/// A solid's or obstacle's canvas (`<canvas>`): the kernel's image and what draws it.
struct CanvasRef {
  ImageHandle image;
  std::unique_ptr<CanvasPainter> painter;
};

/// A `spraygun` of SimTwo's world-wide sensor list (SetSprayGunOn(i): the i-th of them).
struct SprayGunRef {
  std::string prefix;
  InputHandle on{-1};  // index -1 when no plugin gives the kind (an inert sensor)
  SignalHandle min_dist{-1};
  /// Per painting target: the resets it carried out, and its paint per triangle.
  std::vector<SignalHandle> resets_seen;
  std::vector<std::vector<SignalHandle>> thickness;
};

/// A painting target (ConfigureContext::painting_targets), SimTwo's i of the paint routines.
struct PaintTargetRef {
  std::string id;
  BodyHandle body;
  std::vector<Vec3> vertices;  // body frame, three per triangle
  /// Per triangle, the triangles that share a vertex with it: neighbors_of[t] to
  /// neighbors_of[t + 1] in neighbors.
  std::vector<int> neighbors_of, neighbors;
  InputHandle resets{-1};  // `paint_targets/<k>/resets`, -1 when no gun paints
  int count() const { return static_cast<int>(vertices.size() / 3); }
};

/// Rotation about world Z.
inline Mat3 rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Mat3{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

class ScriptController final : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

  // The host table's entries (static trampolines to the object).
  static double host_call(void* host, std::int32_t fn, const double* args, std::int32_t nargs,
                          const char* text, std::int32_t text_len, const char* text2,
                          std::int32_t text2_len);
  static std::int32_t host_result(void* host, std::int32_t kind, const void** data);

 private:
  double call(HostFn fn, const double* a, int n, const std::string& s, const std::string& s2);
  /// The robots', solids', things' and obstacles' functions (host_bodies.cpp).
  double call_bodies(HostFn fn, const double* a, int n, const std::string& s);
  /// Things and obstacles added and deleted while running (host_things.cpp).
  double call_things(HostFn fn, const double* a, int n, const std::string& s);
  /// MeshThing: `files` is the mesh file, a NUL, the shadow mesh file.
  double mesh_thing(const double* a, int n, const std::string& id, const std::string& files);
  /// Springs, friction, controller gains and modes, the energy meter (host_axes.cpp).
  double call_axes(HostFn fn, const double* a, int n, const std::string& s);
  /// Trails, charts, the sheet's colours and UDP packets (host_annotations.cpp).
  double call_annotations(HostFn fn, const double* a, int n);
  /// The spray guns and painting targets (host_paint.cpp): configure_paint resolves them.
  void configure_paint(ConfigureContext& ctx);
  double call_paint(HostFn fn, const double* a, int n);
  /// The last <camera> shell's rgb image (host_camera.cpp): GetCameraPixel, CamBitmap.
  void configure_camera(ConfigureContext& ctx);
  double call_camera(HostFn fn, const double* a, int n);
  SprayGunRef& spray_gun(double i);
  /// The canvases (host_canvas.cpp): the kernel's image of each one configure_canvas names,
  /// drawn by the script's TCanvas (a Cairo surface made at the first initialize), copied
  /// into the image after each call when it changed (flush_canvases) and white again at a
  /// reset (clear_canvases).
  int configure_canvas(ConfigureContext& ctx, const std::string& image_name);
  double call_canvas(HostFn fn, const double* a, int n, const std::string& s,
                     const std::string& s2);
  void flush_canvases(StepContext& ctx);
  void clear_canvases(StepContext& ctx);
  PaintTargetRef& paint_target(double i);
  /// Target `k`'s paint per triangle, summed over the guns, into paint_scratch_: a gun that
  /// has not yet carried out the target's last reset counts for nothing (the script sees the
  /// target clear at once, as SimTwo's).
  const double* paint_of(std::size_t k);
  /// A script error naming `fn` when it got fewer than `want` arguments.
  void require_arguments(HostFn fn, int have, int want);
  /// The obstacle of index `t`, or a script error.
  ObstacleRef& obstacle(double t);
  [[noreturn]] void fail(const std::string& message);
  [[noreturn]] void not_provided(HostFn fn, const char* why);
  RobotRef& robot(double r);
  AxisRef& axis(double r, double i);
  /// The axis itself when it has a DC motor; a script error otherwise.
  const AxisRef& motor(const AxisRef& ax);
  SensorRef& robot_sensor(double r, double i);
  SensorRef& global_sensor(double i);
  SolidRef& solid(double r, double i);
  /// The XY series id the viewer gets for SimTwo's (chart, series); raises out of range.
  int chart_series(double chart, double series);
  ThingRef& thing(double t);
  double sensor_value(const SensorRef& s, bool substitute);
  void sensor_values(const SensorRef& s);
  void load_library();
  void report_error(const std::string& routine, const std::string& message);
  /// The script's UDP socket, opened at configure when the script names a UDP routine, else
  /// at its first use (io_ports.hpp).
  UdpPort& udp();
  std::string udp_failure(const std::string& why) const;
  /// The script called Halt: the run ends (close 1 for Halt(0), 2 for another code).
  void report_halt(StepContext& ctx, const std::string& routine, const std::string& message);
  /// "ROUTINE at file:line" of the first frame in the user's file, else the first known.
  std::string where_raised(const std::vector<std::string>& parts) const;

  // The model, from configure().
  std::filesystem::path script_;
  std::filesystem::path library_path_;
  bool available_ = false;  // compiled and loadable
  double period_s_ = kDefaultControlPeriod_s;
  std::uint64_t seed_ = 1;
  std::vector<RobotRef> robots_;
  std::vector<SensorRef> sensors_;  // SimTwo's global list
  std::vector<ThingRef> things_;
  /// The scene's things as loaded: what SimTwo's list holds again at every reset.
  std::vector<ThingRef> things_loaded_;
  std::vector<ObstacleRef> obstacles_loaded_;
  /// SimTwo's one fire effect: where it burns (a solid, or the world at fire_position_), how big.
  struct Fire {
    bool burning = false;
    BodyHandle on{0};
    Vec3 position_m, scale{1, 1, 1};
  } fire_;
  std::vector<ObstacleRef> obstacles_;
  std::vector<SprayGunRef> spray_guns_;
  std::vector<PaintTargetRef> paint_targets_;
  std::vector<double> paint_scratch_;  // sized at configure for the largest target
  std::string camera_prefix_;          // the last camera shell's; empty: none
  ImageHandle camera_image_;           // its rgb image; index -1: none (no camera plugin)
  std::vector<CanvasRef> canvases_;
  std::vector<std::pair<std::string, double>> constants_;
  std::vector<InputHandle> sheet_inputs_;
  std::vector<double> sheet_initial_values_;  // the inputs' values at reset
  std::vector<std::pair<int, std::string>> key_inputs_;
  std::vector<InputHandle> keys_;
  Sheet sheet_;
  Sheet sheet_initial_;
  std::vector<std::pair<std::string, InputHandle>> sheet_input_names_;
  // [0] started, [1] stopped, [2] calls, then per axis the last encoder count, then per axis
  // the energy meter's zero (ResetAxisEnergy)
  StateHandle state_;
  std::size_t axis_count_ = 0;
  // No "compiled" signal: whether this load found the library in the cache is not part of
  // the run, and a signal of it made the logs of a cold and a warm run differ.
  SignalHandle sig_error_, sig_calls_;
  SignalHandle sig_close_;  // 1 once the script called CloseSimTwo (s2sim-run stops there)
  InputHandle run_input_;
  double last_run_value_ = 1;  // the `running` input as last seen (Run restarts on a change)
  bool loaded_poses_ = false;

  // Run-time state outside the kernel (docs/scripting.md, "State"): the script's own globals,
  // the texts it wrote, its ports.
  ScriptLibrary library_;
  StepContext* ctx_ = nullptr;  // during a call
  std::string pending_error_;
  std::string last_error_;  // the run-time error that stopped the script
  std::string text_result_;
  std::vector<double> numbers_;
  // The bodies a script moved or set moving in this call, as it built them up: SetSolidPos
  // then SetSolidRotationMat on one body make one move (the kernel applies it after the call).
  std::vector<std::pair<std::int32_t, Pose>> moves_;
  std::vector<std::pair<std::int32_t, Twist>> velocities_;
  Pose& move_of(BodyHandle b);
  Twist& velocity_of(BodyHandle b);
  std::deque<std::string> output_;  // WriteLn, the last 100 lines
  // The script's trails as it built them (DelTrailNode redraws a trail less its oldest node)
  // and its charts' series counts (ChartSeriesCreate, ChartSeriesGetCount).
  std::vector<std::deque<Vec3>> trails_;
  std::vector<int> chart_series_count_;
  std::string hud_;
  UdpPort udp_;
  std::string udp_address_ = "127.0.0.1";  // <s2sim><udp address>, S2SIM_UDP_ADDRESS
  int udp_port_ = 9808;                    // <s2sim><udp port>, S2SIM_UDP_PORT
  SerialPort serial_;
  ModbusServer modbus_;
  bool warned_unavailable_ = false;
};

}  // namespace s2sim::pascal
