// Mesh files of imported robots: how their axes and units are read (docs/models/import.md,
// "Meshes").

#include <s2sim/kernel/simulation.hpp>

#include "kernel/import/import_fixtures.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace s2sim {
namespace {

TEST(ImportMeshes, ColladaAxesAreTheLinksAxesWhateverTheUpAxisAndTheUnitIsApplied) {
  auto sim =
      Simulation::load(test::kImportFixtures / "dae_meshes/posts.urdf", test::import_options());
  const scene::Scene& s = sim->scene();
  ASSERT_EQ(s.bodies.size(), 1u);  // the three posts joined by fixed joints
  ASSERT_EQ(s.bodies[0].geoms.size(), 3u);
  for (const scene::Geom& g : s.bodies[0].geoms) {
    const Vec3 size = g.shape.size_m;
    std::printf("%s: hull box %.6f x %.6f x %.6f m\n",
                g.visual.mesh.file.filename().string().c_str(), size.x, size.y, size.z);
    EXPECT_EQ(g.shape.type, scene::ShapeType::convex);
    EXPECT_NEAR(size.x, 0.1, 1e-6) << g.visual.mesh.file;
    EXPECT_NEAR(size.y, 0.2, 1e-6) << g.visual.mesh.file;
    EXPECT_NEAR(size.z, 0.5, 1e-6) << g.visual.mesh.file;
  }
  // Lifted onto the floor: standing on the posts' ends, 0.25 m below the link frame.
  EXPECT_NEAR(sim->body_pose(1).position.z, 0.25, 1e-6);
}

}  // namespace
}  // namespace s2sim
