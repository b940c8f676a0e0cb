// Signal paths: one function per path kind.
#include "sim/names.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace s2sim::sim {
namespace {

TEST(Names, OneFunctionPerPathKind) {
  const std::string r = robot_path("arm/left");  // '/' in an ID becomes '_'
  EXPECT_EQ(r, "robots/arm_left");
  EXPECT_EQ(solid_path(r, "base"), "robots/arm_left/solids/base");
  EXPECT_EQ(thing_path("ball/1"), "things/ball_1");
  EXPECT_EQ(axis_path(r, "J1:2"), "robots/arm_left/axes/J1:2");
  EXPECT_EQ(axis_path(kWorldScope, "door"), "world/axes/door");
  EXPECT_EQ(joint_path(kWorldScope, "hinge"), "world/joints/hinge");
  EXPECT_EQ(joint_path(r, "J1"), "robots/arm_left/joints/J1");
  EXPECT_EQ(component_path(r, "sensors", "ir/0"), "robots/arm_left/sensors/ir_0");
  EXPECT_EQ(component_path("", "controllers", "pilot"), "controllers/pilot");
  EXPECT_EQ(field_path(axis_path(r, "J1"), "pos"), "robots/arm_left/axes/J1/pos");
}

}  // namespace
}  // namespace s2sim::sim
