#pragma once
/// \file
/// The sensor kinds of the `sensors` plugin, one source file each (docs/models/sensors.md).

#include "common.hpp"

#include <vector>

namespace s2sim::sensors {

/// `IRSharp`: distance along one ray; SimTwo's physical 1/d noise model.
class IRSharp : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  SignalHandle value_, valid_;
};

/// One-ray presence sensors: `capacitive` (anything), `inductive` (metallic), `RFID` (the
/// hit body's ID as an integer when it is an RFID tag).
class RayPresence : public Component {
 public:
  enum class Mode { capacitive, inductive, rfid };
  explicit RayPresence(Mode m) : mode_(m) {}
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  Mode mode_;
  SensorSetup s_;
  std::vector<double> rfid_code_;  ///< per body, the integer value of its ID (0 if none)
  SignalHandle value_;
};
class Capacitive : public RayPresence {
 public:
  Capacitive() : RayPresence(Mode::capacitive) {}
};
class Inductive : public RayPresence {
 public:
  Inductive() : RayPresence(Mode::inductive) {}
};
class Rfid : public RayPresence {
 public:
  Rfid() : RayPresence(Mode::rfid) {}
};

/// `solenoid`: detects ferromagnetic surfaces and pulls them with f = ½·Vin·fmax/(1 + k2·d)².
class Solenoid : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  InputHandle vin_;
  SignalHandle value_, force_;
};

/// `floorline`: fraction of a side×side ray grid whose floor point lies on a tagged track.
class FloorLine : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  bool inside(double x, double y) const;
  SensorSetup s_;
  int side_ = 3;
  double pitch_ = 0;
  std::vector<double> vx_, vy_;                ///< vertices of the matching polygons, concatenated
  std::vector<std::size_t> poly_start_;        ///< polygon k: [poly_start_[k], poly_start_[k + 1])
  std::vector<double> bx0_, by0_, bx1_, by1_;  ///< polygon bounds
  SignalHandle value_;
};

/// `ranger2d`: a fan of rays in the sensor's XY plane, swept over its period (SimTwo) or all
/// at once (`<scan mode='instant'/>`).
class Ranger2D : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  double cast(StepContext& ctx, const Pose& world, int i) const;
  void add_noise(StepContext& ctx, double* distances, int first, int last) const;
  SensorSetup s_;
  bool sweep_ = true;
  int n_ = 3;
  std::vector<Vec3> dirs_;  ///< per ray, in the sensor frame
  const ZigguratTables* zig_ = nullptr;
  std::vector<SignalHandle> rays_;
  StateHandle pending_;  ///< the distances measured so far in this period
  SignalHandle sweeps_;
  StateHandle sweep_count_;
};

/// `lidar3d`: channels × azimuth steps of rays from one origin, every period: a range image
/// (`range`, float32), a point cloud in the sensor frame (`points`, xyz_float32), the number
/// of hits and the nearest range.
class Lidar3D : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  int rows_ = 16, cols_ = 1800;  ///< channels, azimuth steps
  double min_m_ = 0.1, max_m_ = 100;
  std::vector<double> cos_el_, sin_el_;  ///< per image row (row 0 = the highest channel)
  std::vector<double> cos_az_, sin_az_;  ///< per image column
  const ZigguratTables* zig_ = nullptr;
  ImageHandle range_, points_;
  SignalHandle hits_, nearest_;
};

/// `sonar`: a cone (half angle = beam angle / 2) of rays; the nearest echo.
class Sonar : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  std::vector<Vec3> dirs_;
  SignalHandle value_;
};

/// `camera`: colour, depth and segmentation images drawn by the simulation's renderer
/// (`StepContext::render_camera`), with pixel and depth noise; also made from a `<camera>`
/// shell.
class CameraSensor : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  CameraShot shot_;  ///< its pose is the camera frame in the sensor frame
  ImageHandle rgb_, depth_, ids_;
  bool want_rgb_ = true, want_depth_ = false, want_ids_ = false;
  GenericNoise depth_noise_;
  const ZigguratTables* zig_ = nullptr;
  SignalHandle frames_;
};

/// `imu`: accelerometer (specific force) and gyroscope in the sensor frame, with bias,
/// white noise and bias random walk.
class Imu : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  struct Channel {
    double noise = 0;      ///< white noise stdev per sample
    double bias = 0;       ///< stdev of the bias drawn at reset
    double bias_walk = 0;  ///< random walk density, per sqrt(s)
    double bias_mean = 0;
  };
  SensorSetup s_;
  Channel acc_, gyro_;
  SignalHandle acc_sig_[3], gyro_sig_[3];
  StateHandle prev_v_;  ///< previous point velocity (3) and a "has previous" flag
  StateHandle bias_;    ///< acc bias (3), gyro bias (3)
};

/// `pose`: GPS-like noisy ground truth of the sensor frame (x, y, z, yaw).
class PoseSensor : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  double yaw_stdev_ = 0;
  SignalHandle x_, y_, z_, yaw_;
};

/// `touch`: contacts on the sensor's body (optionally only inside a box around the sensor).
class Touch : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  bool region_ = false;
  Vec3 half_;  ///< region half size in the sensor frame
  double threshold_N_ = 0;
  SignalHandle value_, force_;
};

/// `pentip`: touches a `canvas` face (within 0.1 mm along its beam).
class PenTip : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  SignalHandle value_, x_, y_;
};

/// `jointforce`: the reaction force and torque a joint transmits (body2 on body1, torque
/// about the anchor, body1's frame): `fx fy fz` (N), `tx ty tz` (N·m).
class JointForce : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  JointHandle joint_;
  BodyHandle body1_;
  SignalHandle force_[3], torque_[3];
};

/// `beacon`: a visual marker; publishes its world position.
class Beacon : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  SensorSetup s_;
  SignalHandle x_, y_, z_;
};

/// `spraygun`: deposits paint on every painting target's triangles inside its cone
/// (spray_model.hpp), through the on/off input `on`; per triangle the thickness of its own
/// paint, in its state, published as `paint/<target>/<triangle>` (m).
class SprayGun : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

 private:
  struct Triangle {
    Vec3 a, b, c;  ///< vertices, body frame
    Vec3 centre;   ///< body frame
    Vec3 normal;   ///< unit, body frame: the side the vertices turn anticlockwise on
    double area_m2 = 0;
  };
  struct Target {
    BodyHandle body;
    int first = 0, count = 0;  ///< its triangles in triangles_
    InputHandle resets;        ///< `paint_targets/<k>/resets`, shared by every gun
    SignalHandle resets_seen;  ///< `paint/<k>/resets`: the resets this gun has carried out
  };
  void read_paint(ConfigureContext& ctx);
  bool occluded(StepContext& ctx, const Vec3& nozzle, const Vec3& to, double distance,
                BodyHandle target) const;
  void publish_all(StepContext& ctx);
  SensorSetup s_;
  double rate_m3_s_ = 0.01, max_angle_rad_ = 0.2, sigma_rad_ = 0.1, cos_max_ = 1, per_sr_ = 0;
  bool occlusion_ = false;
  std::vector<Triangle> triangles_;
  std::vector<Target> targets_;
  std::vector<SignalHandle> thickness_sig_;  ///< per triangle
  InputHandle on_;
  StateHandle thickness_, resets_done_;  ///< per triangle (m); per target
  double color_[3] = {1, 0, 0};          ///< paint_color_rgb, 0..1
  SignalHandle volume_, min_dist_, color_sig_[3];
};

}  // namespace s2sim::sensors
