// The viewer's parts that need no window: meshes (primitives, track polygons, files through
// assimp), the camera, the chart's CSV export and run control's pacing.
#include <camera.hpp>
#include <chart_data.hpp>
#include <mesh_data.hpp>
#include <run_control.hpp>

#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace s2sim::viewer {
namespace {

namespace fs = std::filesystem;

const fs::path kDefaultScene = fs::path(S2SIM_SOURCE_DIR) / "scenes/default";

fs::path temp_file(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("s2sim_viewer_core_" + name);
}

/// Area of a mesh's triangles projected on XY.
double xy_area(const MeshData& m) {
  double area = 0;
  for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    const float* a = m.vertices[m.indices[i]].position;
    const float* b = m.vertices[m.indices[i + 1]].position;
    const float* c = m.vertices[m.indices[i + 2]].position;
    area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  return area;
}

TEST(Meshes, UnitBoxHasOutwardCounterClockwiseFaces) {
  const MeshData box = unit_box();
  ASSERT_EQ(box.indices.size(), 36u);
  for (std::size_t i = 0; i < box.indices.size(); i += 3) {
    const Vertex& a = box.vertices[box.indices[i]];
    const Vertex& b = box.vertices[box.indices[i + 1]];
    const Vertex& c = box.vertices[box.indices[i + 2]];
    const Vec3f ab{b.position[0] - a.position[0], b.position[1] - a.position[1],
                   b.position[2] - a.position[2]};
    const Vec3f ac{c.position[0] - a.position[0], c.position[1] - a.position[1],
                   c.position[2] - a.position[2]};
    const Vec3f n = cross(ab, ac);
    EXPECT_GT(dot(n, {a.normal[0], a.normal[1], a.normal[2]}), 0) << "triangle " << i / 3;
  }
}

TEST(Meshes, ConcavePolygonIsTriangulatedWithItsAreaFacingUp) {
  // An L shape (area 3), given clockwise: ear clipping must not cover the notch.
  const std::vector<std::pair<double, double>> l_shape = {{0, 0}, {0, 2}, {1, 2},
                                                          {1, 1}, {2, 1}, {2, 0}};
  const MeshData m = flat_polygon(l_shape);
  EXPECT_EQ(m.indices.size(), 3u * 4u);
  EXPECT_NEAR(xy_area(m), 3.0, 1e-9);
  EXPECT_TRUE(flat_polygon({{0, 0}, {1, 0}}).indices.empty());
}

TEST(Meshes, FilesLoadThroughAssimpWithTheirScale) {
  // The same triangle as ASCII STL, OBJ and PLY, scaled by 2.
  const std::string stl =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid t\n";
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"tri.stl", stl}, {"tri.obj", obj}, {"tri.ply", ply}}) {
    const fs::path file = temp_file(name);
    std::ofstream(file) << text;
    const MeshData m = load_mesh_file(file, 2.0);
    ASSERT_EQ(m.indices.size(), 3u) << name;
    EXPECT_NEAR(std::abs(xy_area(m)), 2.0, 1e-6) << name;  // (0.5 * 1 * 1) * 2^2
  }
}

TEST(Meshes, UnreadableFileIsASceneErrorNamingIt) {
  const fs::path file = temp_file("broken.stl");
  std::ofstream(file) << "this is not a mesh";
  try {
    load_mesh_file(file, 1.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    EXPECT_NE(std::string(e.what()).find("broken.stl"), std::string::npos) << e.what();
  }
}

TEST(Camera, ProjectsItsTargetToTheCentreAndZoomsTowardIt) {
  Camera camera;
  camera.target_m = {1, 2, 0.5f};
  const Mat4 vp = camera.projection(16.0f / 9) * camera.view();
  const Vec4f c = vp * Vec4f{1, 2, 0.5f, 1};
  EXPECT_NEAR(c.x / c.w, 0, 1e-5);
  EXPECT_NEAR(c.y / c.w, 0, 1e-5);
  const float before = camera.distance_m;
  camera.zoom(1);
  EXPECT_LT(camera.distance_m, before);
  const Mat4 round_trip = inverse(vp) * vp;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(round_trip.at(i, j), i == j ? 1 : 0, 1e-4);
}

TEST(RunControl, PacesTicksToWallTimeTimesSpeedAndStepsWhilePaused) {
  auto sim = Simulation::load(kDefaultScene);
  ChartData chart;
  RunControl run;
  run.speed = 2;
  // 0.05 s of wall time at 2x is 100 ticks of 1 ms.
  EXPECT_EQ(run.advance(*sim, 0.05, chart, true), 100);
  EXPECT_EQ(sim->tick(), 100);
  run.playing = false;
  EXPECT_EQ(run.advance(*sim, 0.05, chart, true), 0);
  run.request_step(3);
  EXPECT_EQ(run.advance(*sim, 0.05, chart, true), 3);
  run.request_reset();
  run.advance(*sim, 0.05, chart, true);
  EXPECT_EQ(sim->tick(), 0);
  run.playing = true;
  run.pause_at_s = 0.02;
  run.as_fast_as_possible = true;
  run.advance(*sim, 0.05, chart, true);
  EXPECT_EQ(sim->tick(), 20);
  EXPECT_FALSE(run.playing);
}

// ../shared/repro (issue 16): the viewer's Reset forgot the --set inputs, so a reset run was
// not the run it had started as. Reset replays it tick for tick.
TEST(RunControl, ResetKeepsTheHeldInputsAndReplaysTheRun) {
  auto sim = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt");
  const std::string input = "robots/nxt/axes/right/ref_voltage";
  ChartData chart;
  RunControl run;
  run.held_inputs = {{input, 6.0}};
  sim->set_input(input, 6.0);  // as load_simulation does with --set
  run.as_fast_as_possible = true;
  run.pause_at_s = 0.3;
  run.advance(*sim, 0.05, chart, true);
  const double speed = sim->signal("robots/nxt/axes/right/speed");
  const double x = sim->signal("robots/nxt/x");
  EXPECT_GT(speed, 1.0) << "the held voltage drives the wheel";
  run.request_reset();
  run.playing = true;
  run.advance(*sim, 0.05, chart, true);
  EXPECT_EQ(sim->input(sim->input_index(input)), 6.0);
  EXPECT_EQ(sim->signal("robots/nxt/axes/right/speed"), speed);
  EXPECT_EQ(sim->signal("robots/nxt/x"), x);
}

TEST(ChartData, RecordsEveryTickAndExportsTheRunnersFormat) {
  auto sim = Simulation::load(kDefaultScene);
  ChartData chart;
  chart.add_signal(sim->signal_index("robots/pendulum/axes/swing/pos"));
  chart.record(*sim);
  RunControl run;
  run.as_fast_as_possible = true;
  run.pause_at_s = 0.003;
  run.advance(*sim, 0.0, chart, true);
  ASSERT_EQ(chart.times_s().size(), 4u);
  const fs::path file = temp_file("chart.csv");
  ASSERT_EQ(chart.export_csv(file.string(), *sim), "");
  std::ifstream in(file);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header, "time [s],robots/pendulum/axes/swing/pos [rad]");
  EXPECT_EQ(first, "0.000000,0");
  // A signal added later has no earlier samples: NaN, not a made-up value.
  chart.add_signal(sim->signal_index("robots/pendulum/axes/swing/speed"));
  EXPECT_TRUE(std::isnan(chart.values(1)[0]));
  EXPECT_NE(chart.export_csv("/nonexistent/dir/x.csv", *sim), "");
}

}  // namespace
}  // namespace s2sim::viewer
