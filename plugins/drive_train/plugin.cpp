/// \file
/// The drive_train plugin: its descriptor.

#include "components.hpp"

#include <s2sim/plugin.hpp>

S2SIM_PLUGIN("drive_train",
             S2SIM_KIND("dc_motor", s2sim::Category::actuator, s2sim::drive_train::DcMotor),
             S2SIM_KIND("encoder", s2sim::Category::sensor, s2sim::drive_train::Encoder),
             S2SIM_KIND("motor_controller", s2sim::Category::controller,
                        s2sim::drive_train::MotorController));
