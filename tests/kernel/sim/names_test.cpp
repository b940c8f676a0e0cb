// Signal paths (one function per path kind) and the kernel's internal assertion.
#include "sim/names.hpp"
#include "common/assert.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace s2sim::sim {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

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

TEST(Assert, ThrowsALocatedInternalError) {
  EXPECT_NO_THROW(S2SIM_ASSERT(1 + 1 == 2, "arithmetic"));
  try {
    const int size = 3, index = 5;
    S2SIM_ASSERT(index < size, "index past the table");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_THAT(e.message(), StartsWith("internal error: index past the table (index < size) at "));
    EXPECT_THAT(e.message(), HasSubstr("tests/kernel/sim/names_test.cpp:"));
  }
}

}  // namespace
}  // namespace s2sim::sim
