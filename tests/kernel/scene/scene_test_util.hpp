#pragma once
// Helpers shared by the scene loader tests: fixture paths, lookups, vector comparisons.

#include <s2sim/kernel/scene.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace s2sim::scene::testing {

inline std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures" / name;
}

inline std::filesystem::path shared_scene(const std::string& name) {
  return std::filesystem::path(S2SIM_SHARED_SCENES) / name;
}

inline bool shared_scenes_present() {
  return std::filesystem::is_directory(S2SIM_SHARED_SCENES);
}

#define S2SIM_SKIP_WITHOUT_SHARED_SCENES()               \
  if (!::s2sim::scene::testing::shared_scenes_present()) \
  GTEST_SKIP() << S2SIM_SHARED_SCENES << ": …/shared/simtwo-scenes absent"

/// Index of the body of `robot` (-1 = things) with `id`, or -1.
inline int body_index(const Scene& s, int robot, const std::string& id) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (s.bodies[i].robot == robot && s.bodies[i].id == id) return static_cast<int>(i);
  return -1;
}

inline const Body& body(const Scene& s, int robot, const std::string& id) {
  const int i = body_index(s, robot, id);
  EXPECT_GE(i, 0) << "no body " << id << " in robot " << robot;
  return s.bodies.at(static_cast<std::size_t>(i < 0 ? 0 : i));
}

inline const Joint& joint(const Scene& s, int robot, const std::string& id) {
  for (const Joint& j : s.joints)
    if (j.robot == robot && j.id == id) return j;
  ADD_FAILURE() << "no joint " << id << " in robot " << robot;
  return s.joints.at(0);
}

inline const Sensor& sensor(const Scene& s, const std::string& id) {
  for (const Sensor& x : s.sensors)
    if (x.id == id) return x;
  ADD_FAILURE() << "no sensor " << id;
  return s.sensors.at(0);
}

inline ::testing::AssertionResult near_vec(const Vec3& actual, const Vec3& expected,
                                           double tol = 1e-12) {
  if (std::abs(actual.x - expected.x) <= tol && std::abs(actual.y - expected.y) <= tol &&
      std::abs(actual.z - expected.z) <= tol)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "(" << actual.x << ", " << actual.y << ", " << actual.z << ") != (" << expected.x
         << ", " << expected.y << ", " << expected.z << ")";
}

inline ::testing::AssertionResult near_mat(const Mat3& actual, const Mat3& expected,
                                           double tol = 1e-12) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(actual.m[i][j] - expected.m[i][j]) > tol)
        return ::testing::AssertionFailure()
               << "element [" << i << "][" << j << "]: " << actual.m[i][j]
               << " != " << expected.m[i][j];
  return ::testing::AssertionSuccess();
}

/// Loads `path` expecting an s2sim::Error; returns it.
inline Error load_error(const std::filesystem::path& path) {
  try {
    load_scene(path);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "loading " << path << " did not throw";
  return Error(ErrorKind::runtime, "no error");
}

inline bool has_warning(const Scene& s, const std::string& fragment) {
  for (const auto& w : s.warnings)
    if (w.find(fragment) != std::string::npos) return true;
  return false;
}

}  // namespace s2sim::scene::testing
