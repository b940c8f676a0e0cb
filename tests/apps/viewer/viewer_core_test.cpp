// The viewer's parts that need no window: meshes (primitives, track polygons, files through
// assimp), the camera, the chart's CSV export and run control's pacing.
#include <camera.hpp>
#include <chart_data.hpp>
#include <keep_in_view.hpp>
#include <layout.hpp>
#include <mesh_data.hpp>
#include <run_control.hpp>
#include <simtwo_camera.hpp>
#include <stepper.hpp>
#include <trails.hpp>

#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include "common/temp_dir.hpp"

namespace s2sim::viewer {
namespace {

namespace fs = std::filesystem;
using render::flat_polygon;
using render::load_mesh_file;
using render::MeshData;
using render::unit_box;
using render::unit_cylinder;
using render::unit_sphere;
using render::Vertex;

const fs::path kDefaultScene = fs::path(S2SIM_SOURCE_DIR) / "scenes/default";

fs::path temp_file(const std::string& name) {
  return s2sim::test::process_temp_dir() / ("s2sim_viewer_core_" + name);
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

TEST(Meshes, ColladaAxesAreTheFilesAxesWhateverItsUpAxisAsTheCollisionHullsAre) {
  // A 0.1 x 0.2 x 0.5 m box tall along the file's z, marked Z_UP, in centimetres: drawn tall
  // along z (assimp alone would turn it to Y-up), in metres.
  const fs::path file =
      fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/scene/fixtures/import/dae_meshes/tall_z_up_cm.dae";
  const MeshData m = load_mesh_file(file, 1.0);
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (const Vertex& v : m.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v.position[k]);
      hi[k] = std::max(hi[k], v.position[k]);
    }
  EXPECT_NEAR(hi[0] - lo[0], 0.1, 1e-5);
  EXPECT_NEAR(hi[1] - lo[1], 0.2, 1e-5);
  EXPECT_NEAR(hi[2] - lo[2], 0.5, 1e-5);
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

// The camera starts framed. Whatever the box, its corners land inside the view.
TEST(Camera, FrameBoxPutsEveryCornerInsideTheView) {
  struct Case {
    Vec3f lo, hi;
    float aspect;
  };
  for (const Case& c : {Case{{-0.1f, -0.1f, 0}, {0.1f, 0.1f, 0.2f}, 16.0f / 9},
                        Case{{-3, -1, 0}, {5, 1, 0.5f}, 1.9f}, Case{{0, 0, 0}, {1, 20, 3}, 1.0f},
                        Case{{-40, -40, 0}, {40, 40, 2}, 0.5f}}) {
    Camera camera;
    camera.frame_box(c.lo, c.hi, c.aspect);
    const Mat4 vp = camera.projection(c.aspect) * camera.view();
    float largest = 0;
    for (int k = 0; k < 8; ++k) {
      const Vec4f h =
          vp * Vec4f{k & 1 ? c.hi.x : c.lo.x, k & 2 ? c.hi.y : c.lo.y, k & 4 ? c.hi.z : c.lo.z, 1};
      ASSERT_GT(h.w, 0);
      largest = std::max({largest, std::abs(h.x / h.w), std::abs(h.y / h.w)});
    }
    EXPECT_LE(largest, 0.85f + 1e-4f);
    EXPECT_GT(largest, 0.8f) << "framed, not lost in the distance";
  }
}

// A SimTwo project opens with its author's camera: the eye from config_Viewer.ini,
// the point looked at from config_Params.ini (SimTwo.ini when those are missing).
TEST(SimTwoCamera, ReadsTheProjectsSavedEyeAndTarget) {
  const std::filesystem::path dir =
      s2sim::test::process_temp_dir() / ("s2sim_simtwo_camera_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EXPECT_FALSE(read_simtwo_camera(dir)) << "no settings, no camera";
  std::ofstream(dir / "SimTwo.ini")
      << "[Viewer]\r\nGLDummyCamPos_PositionX=0.77\r\n"
         "GLDummyCamPos_PositionY=-1.03\r\nGLDummyCamPos_PositionZ=1.29\r\n"
         "[Config]\r\nEditSetCamLookX_Text=0.25\r\n"
         "EditSetCamLookY_Text=0.10\r\nEditSetCamLookZ_Text=0.02\r\n";
  auto saved = read_simtwo_camera(dir);
  ASSERT_TRUE(saved);
  EXPECT_FLOAT_EQ(saved->eye_m.y, -1.03f);
  EXPECT_FLOAT_EQ(saved->target_m.x, 0.25f);
  std::ofstream(dir / "config_Viewer.ini")
      << "GLDummyCamPos_PositionX=1.41\nGLDummyCamPos_PositionY=0.03\n"
         "GLDummyCamPos_PositionZ=0.88\n";
  saved = read_simtwo_camera(dir);
  ASSERT_TRUE(saved);
  EXPECT_FLOAT_EQ(saved->eye_m.x, 1.41f) << "config_Viewer.ini comes first";
  Camera camera;
  camera.look_from(saved->eye_m, saved->target_m);
  const Vec3f eye = camera.eye_m();
  EXPECT_NEAR(eye.x, 1.41f, 1e-4f);
  EXPECT_NEAR(eye.y, 0.03f, 1e-4f);
  EXPECT_NEAR(eye.z, 0.88f, 1e-4f);
  std::ofstream(dir / "config_Viewer.ini") << "GLDummyCamPos_PositionX=left\n";
  EXPECT_TRUE(read_simtwo_camera(dir)) << "a bad file falls back to SimTwo.ini";
  std::filesystem::remove_all(dir);
}

// A robot's trail keeps its recent path, skips standing still, starts anew on a
// reset and overwrites its oldest points when full.
TEST(Trails, KeepTheRecentPathOfEachRobot) {
  Trails trails;
  trails.reset(2);
  for (int i = 0; i <= 100; ++i)
    trails.add(0, i * 0.1, {i * 0.01f, 0, 0});  // 1 cm every 0.1 s for 10 s
  trails.add(0, 10.1, {1.0f, 0.001f, 0});       // under 5 mm: not a new point
  EXPECT_EQ(trails.count(0, 100), 101u);
  EXPECT_EQ(trails.count(0, 2.0), 21u) << "the last 2 s";
  const std::size_t n = trails.count(0, 2.0);
  EXPECT_FLOAT_EQ(trails.point(0, n, 0).x, 0.8f);
  EXPECT_FLOAT_EQ(trails.point(0, n, n - 1).x, 1.0f);
  EXPECT_EQ(trails.count(1, 100), 0u) << "the other robot did not move";
  trails.add(0, 0.0, {5, 5, 0});  // the simulation was reset
  EXPECT_EQ(trails.count(0, 100), 1u);
  for (std::size_t i = 1; i <= Trails::capacity + 10; ++i)
    trails.add(1, i * 0.01, {i * 0.01f, 0, 0});
  EXPECT_EQ(trails.count(1, 1e9), Trails::capacity);
  EXPECT_FLOAT_EQ(trails.point(1, Trails::capacity, 0).x, 0.11f) << "the oldest overwritten";
}

// The tiled layout never lets the panels take more than half the window, and they
// never overlap the 3-D view or each other, whatever the window size and column fractions.
TEST(Layout, PanelsTileAroundAViewOfAtLeastHalfTheWindow) {
  for (const auto& [w, h] : {std::pair{1280.0f, 720.0f}, {800.0f, 600.0f}, {1920.0f, 1080.0f}})
    for (float left : {0.0f, 0.25f, 0.5f})
      for (float bottom : {0.0f, 0.3f, 0.9f}) {
        LayoutFractions f;
        f.left = left;
        f.bottom = bottom;
        const TiledLayout l = compute_layout(w, h, 19, 170, f, true, true, true);
        EXPECT_GE(l.world.area(), 0.5f * w * h) << w << "x" << h << " " << left << " " << bottom;
        const Rect rects[] = {l.menu, l.run, l.left, l.bottom, l.world};
        for (const Rect& a : rects)
          for (const Rect& b : rects)
            if (&a != &b) {
              EXPECT_FALSE(a.overlaps(b));
            }
        EXPECT_FLOAT_EQ(l.bottom.y + l.bottom.height, h) << "the bottom row reaches the bottom";
        EXPECT_FLOAT_EQ(l.world.x + l.world.width, w) << "the view reaches the right edge";
      }
  const TiledLayout bare = compute_layout(1280, 720, 0, 170, {}, false, false, false);
  EXPECT_FLOAT_EQ(bare.world.area(), 1280.0f * 720) << "no panels: the view is the window";
}

// The Run window once showed "0.00x" for the first half second (30 frames at 60 fps),
// because the factor was only computed when a half-second window of frame times closed.
TEST(RtfMeter, IsSimulatedOverWallTimeFromTheSecondFrameOn) {
  RtfMeter meter;
  EXPECT_EQ(meter.rtf(), 0);
  meter.sample(100.0, 0.0);
  EXPECT_EQ(meter.rtf(), 0) << "one sample has no rate";
  meter.sample(100.0 + 1.0 / 60, 1.0 / 60);
  EXPECT_NEAR(meter.rtf(), 1.0, 1e-9);
  // 30 frames at 2x, then 30 frames at 0.5x: after the second half second only those count.
  double wall_s = 100.0 + 1.0 / 60, sim_s = 1.0 / 60;
  for (int i = 0; i < 30; ++i)
    meter.sample(wall_s += 1.0 / 60, sim_s += 2.0 / 60);
  EXPECT_NEAR(meter.rtf(), 2.0, 0.07);
  for (int i = 0; i < 31; ++i)
    meter.sample(wall_s += 1.0 / 60, sim_s += 0.5 / 60);
  EXPECT_NEAR(meter.rtf(), 0.5, 1e-9);
  // A thousand fast frames overflow the ring: the factor still uses the ones kept.
  for (int i = 0; i < 1000; ++i)
    meter.sample(wall_s += 1e-4, sim_s += 3e-4);
  EXPECT_NEAR(meter.rtf(), 3.0, 1e-6);
  meter.clear();
  EXPECT_EQ(meter.rtf(), 0);
}

// ../shared/repro: the viewer's Reset once forgot the --set inputs, so a reset run was
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

// The chart keeps the last span of simulated time, and no more numbers than its
// bound, whatever is charted and however long the run; once grown it does not grow further.
TEST(ChartData, KeepsTheLastSpanAndAtMostItsBoundOfNumbers) {
  auto sim = Simulation::load(kDefaultScene);  // 1 ms ticks
  ChartData chart;
  chart.set_span(0.5);
  chart.add_signal(sim->signal_index("robots/pendulum/axes/swing/pos"));
  chart.record(*sim);
  for (int i = 0; i < 2000; ++i) {
    sim->step();
    chart.record(*sim);
  }
  EXPECT_EQ(chart.sample_count(), 501u);
  EXPECT_NEAR(chart.time_s(0), 1.5, 1e-9);
  EXPECT_NEAR(chart.times_s().back(), 2.0, 1e-9);
  const std::size_t grown = chart.stored_values();
  for (int i = 0; i < 3000; ++i) {
    sim->step();
    chart.record(*sim);
  }
  EXPECT_EQ(chart.stored_values(), grown) << "a steady span allocates no more";

  // Every signal: the bound, not the span, decides.
  ChartData all;
  all.set_span(3600);
  for (std::size_t i = 0; i < sim->signal_count(); ++i)
    if (sim->signal_info(i).name != "time") all.add_signal(i);
  const std::size_t per_sample = all.signals().size() + 1;
  const std::size_t steps = 13 * ChartData::kMaxStoredValues / per_sample / 10;
  for (std::size_t i = 0; i < steps; ++i) {
    sim->step();
    all.record(*sim);
  }
  EXPECT_LE(all.sample_count() * per_sample, ChartData::kMaxStoredValues);
  EXPECT_LE(all.stored_values(), ChartData::kMaxStoredValues * 11 / 10);
  EXPECT_NEAR(all.times_s().back(), sim->time_s(), 1e-9) << "the newest sample is kept";
}

// The stepping thread: a job's exception reaches the window's thread; a job that does not
// return can be given up, and the next job runs on a new thread meanwhile.
TEST(Stepper, RethrowsAJobsErrorAndGivesUpAJobThatDoesNotReturn) {
  Stepper stepper;
  EXPECT_TRUE(stepper.idle());
  int runs = 0;
  stepper.start([&] { ++runs; });
  EXPECT_TRUE(stepper.wait(10));
  EXPECT_EQ(runs, 1);
  stepper.start([] { throw std::runtime_error("from the job"); });
  EXPECT_THROW(stepper.wait(10), std::runtime_error);
  EXPECT_TRUE(stepper.idle());

  static std::atomic<bool> release{false};  // outlives the abandoned job, as the docs ask
  static std::atomic<bool> returned{false};
  stepper.start([] {
    while (!release)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    returned = true;
  });
  EXPECT_FALSE(stepper.wait(0.05));
  EXPECT_FALSE(stepper.idle());
  stepper.abandon();
  EXPECT_TRUE(stepper.idle());
  EXPECT_TRUE(stepper.abandoned_any());
  stepper.start([&] { runs = 10; });
  EXPECT_TRUE(stepper.wait(10));
  EXPECT_EQ(runs, 10);
  release = true;  // the abandoned thread ends once its job returns
  for (int i = 0; i < 1000 && !returned; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(returned);
}

// With a gate, advance() lets go of it while the simulation steps, and once the gate is
// abandoned during a step it returns without touching the chart or the run control again.
TEST(RunControl, AnAbandonedGateEndsTheAdvanceAfterTheStepItIsIn) {
  auto sim = Simulation::load(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes/default");
  ChartData chart;
  RunControl run;
  StepGate gate;
  {
    std::lock_guard<std::mutex> lock(gate.mutex);
    EXPECT_EQ(run.advance(*sim, 0.01, chart, true, &gate), 10);
  }
  // The gate is free between advances and during steps: another thread abandons it.
  run.request_step(1000000);
  std::atomic<bool> abandoned{false};
  std::thread window([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::lock_guard<std::mutex> lock(gate.mutex);
    gate.abandoned = true;
    abandoned = true;
  });
  std::int64_t done = 0;
  {
    std::lock_guard<std::mutex> lock(gate.mutex);
    done = run.advance(*sim, 0.0, chart, true, &gate);
  }
  window.join();
  EXPECT_TRUE(abandoned);
  EXPECT_LT(done, 1000000) << "the advance ended early";
  EXPECT_EQ(sim->tick(), 10 + done + 1) << "the step it was in finished; none after";
}

// The quadrotor left the view after 2 s (the camera framed the scene once). A robot that
// touches nothing and leaves the view's central part is to be followed; one on the floor is
// not, and neither is one the user stopped following.
TEST(KeepInView, FollowsARobotThatTouchesNothingNotOneOnTheFloor) {
  Camera camera;  // looking level at the start, close: 1 m up is outside the view
  camera.target_m = {0, 0, 0.1f};
  camera.distance_m = 1.0f;
  camera.pitch_rad = 0;
  const Mat4 vp = camera.projection(16.0f / 9) * camera.view();

  auto quad = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/quadrotor");
  EXPECT_EQ(robot_leaving_view(*quad, vp, {}), -1) << "on the floor, in the view";
  quad->run_until(3.0);  // hovering at 1 m
  EXPECT_EQ(robot_leaving_view(*quad, vp, {}), 0);
  EXPECT_EQ(robot_leaving_view(*quad, vp, {true}), -1) << "declined";
  Camera above = camera;
  above.target_m = to_f(quad->body_pose(quad->scene().robots[0].main_body + 1).position);
  EXPECT_EQ(robot_leaving_view(*quad, above.projection(16.0f / 9) * above.view(), {}), -1)
      << "in the view";

  auto nxt = Simulation::load(fs::path(S2SIM_SOURCE_DIR) / "scenes/nxt");
  nxt->step(100);
  Camera away = camera;
  away.target_m = {20, 20, 0};
  EXPECT_EQ(robot_leaving_view(*nxt, away.projection(16.0f / 9) * away.view(), {}), -1)
      << "out of the view, but on its wheels";

  auto pendulum = Simulation::load(kDefaultScene);  // its bob swings, touching nothing
  EXPECT_EQ(robot_leaving_view(*pendulum, away.projection(16.0f / 9) * away.view(), {}), -1)
      << "jointed to the world";
}

}  // namespace
}  // namespace s2sim::viewer
