// s2sim-camera-bench: camera frames per second of the headless renderer (docs/benchmarks.md,
// "Cameras"), colour alone and depth alone at 320 x 240 and 640 x 480, on scenes/default and
// scenes/pile, beside MuJoCo 2.2's offscreen renderer drawing the same geometry at the same
// poses (the scene as it stands written as MJCF) where MuJoCo is built in; then a 320 x 240
// camera at 30 Hz against the physics of scenes/nxt, both as costs per simulated second.
//
//   s2sim-camera-bench [--seconds 2] [--repeats 3] [--settle 1] [--csv out.csv] [--images DIR]
//
// Each case is timed --repeats times for --seconds of wall time: the best repeat is reported,
// its wall and its process CPU time per frame (llvmpipe draws on threads of its own).
//
// --images writes each engine's colour frames as PPM files into DIR, to see that both drew the
// same scene from the same eye.
#include "camera_bench.hpp"

#include <headless_camera_renderer.hpp>
#include <s2sim/image.hpp>
#include <s2sim/kernel/scene.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace camera_bench;

namespace {

s2sim::CameraShot shot_of(const View& v, Size size) {
  const s2sim::Vec3 eye{v.eye[0], v.eye[1], v.eye[2]};
  const s2sim::Vec3 target{v.target[0], v.target[1], v.target[2]};
  const s2sim::Vec3 forward = target - eye;
  const s2sim::Vec3 z = forward * (1 / s2sim::norm(forward));
  const s2sim::Vec3 left = s2sim::cross(s2sim::Vec3{0, 0, 1}, z);
  const s2sim::Vec3 x = left * (1 / s2sim::norm(left));
  const s2sim::Vec3 y = s2sim::cross(z, x);
  s2sim::CameraShot shot;
  const s2sim::Vec3 columns[3] = {x, y, z};  // the camera frame: +Z forward, +Y up, +X left
  for (int c = 0; c < 3; ++c) {
    shot.pose.rotation.m[0][c] = columns[c].x;
    shot.pose.rotation.m[1][c] = columns[c].y;
    shot.pose.rotation.m[2][c] = columns[c].z;
  }
  shot.pose.position = eye;
  shot.vertical_fov_rad = v.vertical_fov_deg * s2sim::kPi / 180;
  shot.near_m = v.near_m;
  shot.far_m = v.far_m;
  shot.width_px = size.width_px;
  shot.height_px = size.height_px;
  return shot;
}

/// An image over `pixels`, resized for it.
s2sim::Image image_over(std::vector<std::uint8_t>& pixels, Size size, s2sim::PixelFormat f) {
  s2sim::Image image;
  image.width_px = size.width_px;
  image.height_px = size.height_px;
  image.format = f;
  image.stride_bytes = size.width_px * s2sim::bytes_per_pixel(f);
  pixels.assign(image.size_bytes(), 0);
  image.data = pixels.data();
  return image;
}

std::unique_ptr<s2sim::Simulation> load(const fs::path& scene) {
  return s2sim::Simulation::load(scene, s2sim::SimulationOptions{});
}

void step_for(s2sim::Simulation& sim, double seconds) {
  sim.step(static_cast<std::int64_t>(std::llround(seconds / sim.tick_s())));
}

std::vector<Result> s2sim_fps(s2sim::Simulation& sim, const View& view,
                              const std::vector<Size>& sizes, double seconds, int repeats,
                              const std::string& images_path = "") {
  auto renderer = s2sim::render::make_headless_camera_renderer(sim);
  std::vector<Result> results;
  for (const Size& size : sizes)
    for (const bool depth_only : {false, true}) {
      std::vector<std::uint8_t> pixels;
      s2sim::Image image = image_over(
          pixels, size, depth_only ? s2sim::PixelFormat::float32 : s2sim::PixelFormat::rgb8);
      const s2sim::CameraShot shot = shot_of(view, size);
      const auto& poses = sim.body_poses();
      results.push_back(time_frames(size, depth_only, seconds, repeats, [&] {
        renderer->render(shot, poses.data(), static_cast<int>(poses.size()),
                         depth_only ? nullptr : &image, depth_only ? &image : nullptr, nullptr);
      }));
      if (!images_path.empty() && !depth_only)
        write_ppm(images_path + "-" + std::to_string(size.width_px) + ".ppm", image.data, size,
                  false);
    }
  return results;
}

/// The scene as it stands written as MJCF for MuJoCo to draw: every body's and obstacle's
/// boxes, cylinders and spheres as world geoms at their poses now, in their colours, on a
/// plane; with `sun`, a directional light that casts shadows (else MuJoCo's headlight alone).
/// Meshes and convex hulls are left out, counted in `*skipped`.
std::string scene_as_mjcf(const s2sim::Simulation& sim, bool sun, int* skipped) {
  std::string xml = "<mujoco model='camera-bench'><worldbody>";
  if (sun) xml += "<light directional='true' castshadow='true' pos='0 0 5' dir='-0.3 0.4 -1'/>";
  xml += "<geom type='plane' size='0 0 1' rgba='0.8 0.8 0.8 1'/>";
  auto add = [&](const s2sim::scene::Geom& g, const s2sim::Pose& world) {
    char text[512];
    const s2sim::scene::Shape& sh = g.shape;
    if (sh.type == s2sim::scene::ShapeType::box) {
      std::snprintf(text, sizeof text, "type='box' size='%g %g %g'", sh.size_m.x / 2,
                    sh.size_m.y / 2, sh.size_m.z / 2);
    } else if (sh.type == s2sim::scene::ShapeType::cylinder) {
      std::snprintf(text, sizeof text, "type='cylinder' size='%g %g'", sh.radius_m,
                    sh.length_m / 2);
    } else if (sh.type == s2sim::scene::ShapeType::sphere) {
      std::snprintf(text, sizeof text, "type='sphere' size='%g'", sh.radius_m);
    } else {
      ++*skipped;
      return;
    }
    if (!g.visual.mesh.file.empty()) {
      ++*skipped;
      return;
    }
    const s2sim::Mat3& r = world.rotation;
    const s2sim::scene::Color& c = g.visual.color;
    char place[512];
    std::snprintf(place, sizeof place,
                  " pos='%.9g %.9g %.9g' xyaxes='%.9g %.9g %.9g %.9g %.9g %.9g' rgba='%g %g %g %g'",
                  world.position.x, world.position.y, world.position.z, r.m[0][0], r.m[1][0],
                  r.m[2][0], r.m[0][1], r.m[1][1], r.m[2][1], c.r, c.g, c.b, c.a);
    xml += std::string("<geom ") + text + place + "/>";
  };
  const s2sim::scene::Scene& sc = sim.scene();
  std::vector<bool> spare(sc.bodies.size(), false);
  for (int b : sc.runtime_things)
    spare[static_cast<std::size_t>(b)] = true;
  for (std::size_t b = 0; b < sc.bodies.size(); ++b) {
    if (spare[b]) continue;
    const s2sim::Pose& body = sim.body_pose(static_cast<int>(b) + 1);
    for (const s2sim::scene::Geom& g : sc.bodies[b].geoms)
      add(g, body * g.pose);
  }
  for (const s2sim::scene::Geom& g : sc.obstacles)
    add(g, g.pose);
  return xml + "</worldbody></mujoco>\n";
}

struct Row {
  std::string engine, scene;
  Result result;
};

void print_rows(const std::vector<Row>& rows, std::FILE* csv) {
  std::printf("%-10s %-8s %-9s %-6s %7s %9s %8s %13s\n", "engine", "scene", "size", "output",
              "frames", "ms/frame", "fps", "CPU ms/frame");
  for (const Row& r : rows) {
    char size[32];
    std::snprintf(size, sizeof size, "%dx%d", r.result.size.width_px, r.result.size.height_px);
    const char* output = r.result.depth ? "depth" : "rgb";
    std::printf("%-10s %-8s %-9s %-6s %7ld %9.2f %8.1f %13.2f\n", r.engine.c_str(), r.scene.c_str(),
                size, output, r.result.frames, r.result.ms_per_frame, 1e3 / r.result.ms_per_frame,
                r.result.cpu_ms_per_frame);
    if (csv)
      std::fprintf(csv, "%s,%s,%d,%d,%s,%ld,%.3f,%.1f,%.3f\n", r.engine.c_str(), r.scene.c_str(),
                   r.result.size.width_px, r.result.size.height_px, output, r.result.frames,
                   r.result.ms_per_frame, 1e3 / r.result.ms_per_frame, r.result.cpu_ms_per_frame);
  }
}

/// A camera at 320 x 240 and 30 Hz against the physics on scenes/nxt (driving at 6 V): each
/// as wall time and as CPU time per simulated second.
void camera_against_physics(const fs::path& source, double seconds, int repeats, std::FILE* csv) {
  auto sim = load(source / "scenes" / "nxt");
  sim->set_input("robots/nxt/axes/right/ref_voltage", 6.0);
  sim->set_input("robots/nxt/axes/left/ref_voltage", -6.0);
  step_for(*sim, 0.2);
  using Clock = std::chrono::steady_clock;
  double us_per_tick = 0, cpu_us_per_tick = 0;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    const auto start = Clock::now();
    const double cpu_start = process_cpu_s();
    std::int64_t ticks = 0;
    double elapsed = 0;
    while (ticks < 1000 || elapsed < seconds) {
      sim->step(100);
      ticks += 100;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    }
    const double us = 1e6 * elapsed / static_cast<double>(ticks);
    if (repeat == 0 || us < us_per_tick) {
      us_per_tick = us;
      cpu_us_per_tick = 1e6 * (process_cpu_s() - cpu_start) / static_cast<double>(ticks);
    }
  }
  const double ticks_per_s = 1 / sim->tick_s();
  // The robot's view: from the brick's front, level, looking ahead.
  const s2sim::Pose& robot = sim->body_pose(1);
  const s2sim::Vec3 eye = robot * s2sim::Vec3{0.03, 0, 0.1};
  const s2sim::Vec3 ahead = robot * s2sim::Vec3{1.03, 0, 0.1};
  View view;
  view.eye[0] = eye.x, view.eye[1] = eye.y, view.eye[2] = eye.z;
  view.target[0] = ahead.x, view.target[1] = ahead.y, view.target[2] = ahead.z;
  const Result camera = s2sim_fps(*sim, view, {Size{320, 240}}, seconds, repeats).front();
  const double physics_ms = us_per_tick * ticks_per_s / 1e3, camera_ms = camera.ms_per_frame * 30;
  const double physics_cpu_ms = cpu_us_per_tick * ticks_per_s / 1e3,
               camera_cpu_ms = camera.cpu_ms_per_frame * 30;
  std::printf(
      "\nscenes/nxt, per simulated second: physics %.2f us/tick x %.0f ticks/s = %.1f ms wall "
      "(%.1f ms CPU); camera 320x240 rgb %.2f ms x 30 Hz = %.1f ms wall (%.2f ms x 30 = %.1f ms "
      "CPU): the camera costs %.2f x the physics in wall time, %.2f x in CPU time\n",
      us_per_tick, ticks_per_s, physics_ms, physics_cpu_ms, camera.ms_per_frame, camera_ms,
      camera.cpu_ms_per_frame, camera_cpu_ms, camera_ms / physics_ms,
      camera_cpu_ms / physics_cpu_ms);
  if (csv)
    std::fprintf(csv,
                 "# nxt: physics_us_per_tick=%.3f physics_cpu_us_per_tick=%.3f ticks_per_s=%.0f "
                 "camera_320x240_ms=%.3f camera_320x240_cpu_ms=%.3f "
                 "camera_30hz_over_physics_wall=%.3f camera_30hz_over_physics_cpu=%.3f\n",
                 us_per_tick, cpu_us_per_tick, ticks_per_s, camera.ms_per_frame,
                 camera.cpu_ms_per_frame, camera_ms / physics_ms, camera_cpu_ms / physics_cpu_ms);
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 2, settle_s = 1;
  int repeats = 3;
  const char* csv_path = nullptr;
  std::string images_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (a == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--settle" && i + 1 < argc) {
      settle_s = std::atof(argv[++i]);
    } else if (a == "--images" && i + 1 < argc) {
      images_dir = argv[++i];
    } else if (a == "--csv" && i + 1 < argc) {
      csv_path = argv[++i];
    } else {
      std::fprintf(
          stderr,
          "usage: s2sim-camera-bench [--seconds S] [--repeats N] [--settle S] [--csv FILE] "
          "[--images DIR]\n");
      return 2;
    }
  }
  std::FILE* csv = nullptr;
  if (csv_path) {
    csv = std::fopen(csv_path, "w");
    if (!csv) {
      std::perror(csv_path);
      return 1;
    }
    std::fprintf(csv,
                 "engine,scene,width,height,output,frames,ms_per_frame,fps,cpu_ms_per_frame\n");
  }
  const fs::path source = S2SIM_SOURCE_DIR;
  const std::vector<Size> sizes = {{320, 240}, {640, 480}};
  View everything;  // scenes/default: five mechanisms about the origin, 1.5 m apart
  everything.eye[0] = 2.6, everything.eye[1] = -2.6, everything.eye[2] = 1.6;
  everything.target[0] = 0, everything.target[1] = 0, everything.target[2] = 0.4;
  View pile;  // scenes/pile: 150 bodies within 0.4 m of the origin
  pile.eye[0] = 1.2, pile.eye[1] = -1.2, pile.eye[2] = 0.9;
  pile.target[0] = 0, pile.target[1] = 0, pile.target[2] = 0.1;

  std::vector<Row> rows;
  std::string mujoco_note;
  for (const auto& [name, view] : {std::pair{"default", everything}, std::pair{"pile", pile}}) {
    std::unique_ptr<s2sim::Simulation> sim;
    try {
      sim = load(source / "scenes" / name);
      step_for(*sim, settle_s);
      const std::string images = images_dir.empty() ? std::string() : images_dir + "/s2sim-" + name;
      for (const Result& r : s2sim_fps(*sim, view, sizes, seconds, repeats, images))
        rows.push_back({"s2sim", name, r});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "s2sim-camera-bench: S2Sim: %s\n", e.what());
      return 1;
    }
#ifdef S2SIM_CAMERA_BENCH_MUJOCO
    // The same geometry at the same poses in MuJoCo: with its headlight alone, then with a sun
    // that casts shadows as S2Sim's does (a shadow map pass of its own).
    try {
      for (const bool sun : {false, true}) {
        int skipped = 0;
        const std::string label = sun ? "mujoco+sun" : "mujoco";
        const fs::path file =
            fs::temp_directory_path() / ("s2sim-camera-bench-" + label + "-" + name + ".xml");
        std::ofstream(file) << scene_as_mjcf(*sim, sun, &skipped);
        if (skipped > 0 && !sun)
          mujoco_note += std::string("MuJoCo: ") + name + ": " + std::to_string(skipped) +
                         " meshes or hulls left out. ";
        const std::string images =
            images_dir.empty() ? std::string() : images_dir + "/" + label + "-" + name;
        for (const Result& r : mujoco_fps(file.string(), view, sizes, seconds, repeats, 0, images))
          rows.push_back({label, name, r});
        fs::remove(file);
      }
    } catch (const std::exception& e) {
      mujoco_note += std::string("MuJoCo's offscreen renderer did not run: ") + e.what() + ". ";
    }
#else
    mujoco_note = "MuJoCo: not built in (libmujoco-dev not found)";
#endif
  }
  print_rows(rows, csv);
  if (!mujoco_note.empty()) {
    std::printf("%s\n", mujoco_note.c_str());
    if (csv) std::fprintf(csv, "# %s\n", mujoco_note.c_str());
  }
  try {
    camera_against_physics(source, seconds, repeats, csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-camera-bench: scenes/nxt: %s\n", e.what());
    return 1;
  }
  if (csv) std::fclose(csv);
  return 0;
}
