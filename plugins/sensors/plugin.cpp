/// The `sensors` plugin: every sensor kind of SimTwo's format and S2Sim's additions
/// (docs/models/sensors.md).
#include "kinds.hpp"

using namespace s2sim;
using namespace s2sim::sensors;

S2SIM_PLUGIN(
    "sensors", S2SIM_KIND("IRSharp", Category::sensor, IRSharp),
    S2SIM_KIND("capacitive", Category::sensor, Capacitive),
    S2SIM_KIND("inductive", Category::sensor, Inductive),
    S2SIM_KIND("RFID", Category::sensor, Rfid), S2SIM_KIND("solenoid", Category::sensor, Solenoid),
    S2SIM_KIND("spraygun", Category::sensor, SprayGun),
    S2SIM_KIND("floorline", Category::sensor, FloorLine),
    S2SIM_KIND("ranger2d", Category::sensor, Ranger2D),
    S2SIM_KIND("lidar3d", Category::sensor, Lidar3D),
    S2SIM_KIND("pentip", Category::sensor, PenTip), S2SIM_KIND("beacon", Category::sensor, Beacon),
    S2SIM_KIND("imu", Category::sensor, Imu), S2SIM_KIND("pose", Category::sensor, PoseSensor),
    S2SIM_KIND("sonar", Category::sensor, Sonar), S2SIM_KIND("touch", Category::sensor, Touch),
    S2SIM_KIND("jointforce", Category::sensor, JointForce),
    S2SIM_KIND("camera", Category::sensor, CameraSensor))
