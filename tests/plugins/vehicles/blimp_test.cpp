// scenes/blimp: the paper's blimp passes within 0.3 m of each of its waypoints.
#include "scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace s2sim {
namespace {

TEST(Blimp, PassesWithinThirtyCentimetresOfEachWaypoint) {
  auto sim = vehicles_test::load("blimp");
  const double waypoints[4][3] = {{3, 0, 2}, {3, 3, 2.5}, {0, 3, 2}, {0, 0, 1.5}};
  double nearest[4] = {1e9, 1e9, 1e9, 1e9};
  const std::string g = "robots/blimp/solids/gondola/";
  while (sim->time_s() < 90.0 - 1e-9) {
    sim->step(10);
    const double x = sim->signal(g + "x"), y = sim->signal(g + "y"), z = sim->signal(g + "z");
    for (int i = 0; i < 4; ++i)
      nearest[i] = std::min(
          nearest[i], std::hypot(x - waypoints[i][0], y - waypoints[i][1], z - waypoints[i][2]));
  }
  for (int i = 0; i < 4; ++i) {
    std::printf("  waypoint (%g, %g, %g): nearest %.3f m\n", waypoints[i][0], waypoints[i][1],
                waypoints[i][2], nearest[i]);
    EXPECT_LT(nearest[i], 0.3);
  }
  EXPECT_EQ(sim->signal("robots/blimp/controllers/pilot/waypoint"), 4);
}

}  // namespace
}  // namespace s2sim
