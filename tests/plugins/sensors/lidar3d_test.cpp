// The `lidar3d` sensor (docs/models/sensors.md): a 16 × 1 800 scan of a closed box room against
// the analytic ray-plane distances, its conventions, its noise, its period and its errors.
// Each scene is written inline into this process's own temporary folder.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr double kDeg = kPi / 180;

// The room: inner faces at x = ±3, y = ±2, the ground z = 0 and a ceiling at z = 3 (6 m × 4 m
// × 3 m), walls 0.2 m thick.
constexpr double kHalfX = 3, kHalfY = 2, kHeight = 3;

// The robot: a gravity-free 0.3 m cube-ish box centred at (0.7, -0.4, 1.1) (top at 1.2), the
// lidar 0.15 m above its centre, turned by rot_deg (4, -6, 25): off-centre, yawed, tilted.
const Vec3 kBoxCentre{0.7, -0.4, 1.1};
const Vec3 kMount{0, 0, 0.15};
const Vec3 kRotDeg{4, -6, 25};

const char* const kRoom = R"(<?xml version="1.0" ?>
<obstacles>
  <cuboid><ID value='east'/><size x='0.2' y='4.4' z='3.2'/><pos x='3.1' y='0' z='1.6'/></cuboid>
  <cuboid><ID value='west'/><size x='0.2' y='4.4' z='3.2'/><pos x='-3.1' y='0' z='1.6'/></cuboid>
  <cuboid><ID value='north'/><size x='6.4' y='0.2' z='3.2'/><pos x='0' y='2.1' z='1.6'/></cuboid>
  <cuboid><ID value='south'/><size x='6.4' y='0.2' z='3.2'/><pos x='0' y='-2.1' z='1.6'/></cuboid>
  <cuboid><ID value='ceiling'/><size x='6.4' y='4.4' z='0.2'/><pos x='0' y='0' z='3.1'/></cuboid>
</obstacles>
)";

/// The room's 16 × 1 800 lidar on the robot, with `extra` children (noise, period...).
std::string room_lidar(const std::string& extra = "") {
  return "<lidar3d>\n  <ID value='lidar'/>\n  <solid id='base'/>\n"
         "  <pos x='0' y='0' z='0.15'/>\n  <rot_deg x='4' y='-6' z='25'/>\n"
         "  <channels count='16' lowest='-25' highest='15'/>\n"
         "  <azimuth steps='1800' start='-180' stop='180'/>\n"
         "  <range min='0.05' max='100'/>\n" +
         extra + "</lidar3d>\n";
}

/// Writes the room with the robot carrying `robot_sensors` (and `robot_extra` after its
/// `<sensors>`) and the world-fixed `scene_sensors` into a folder of this process named `name`.
fs::path write_scene(const std::string& name, const std::string& robot_sensors,
                     const std::string& scene_sensors = "", const std::string& robot_extra = "") {
  const fs::path dir = test::process_temp_dir() / ("lidar3d_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "room.xml") << kRoom;
  std::ofstream(dir / "bot.xml")
      << "<?xml version=\"1.0\" ?>\n<robot>\n  <solids>\n    <cuboid>\n"
         "      <ID value='base'/>\n      <mass value='1'/>\n"
         "      <size x='0.3' y='0.3' z='0.2'/>\n      <pos x='0.7' y='-0.4' z='1.1'/>\n"
         "      <nogravity/>\n    </cuboid>\n  </solids>\n  <sensors>\n"
      << robot_sensors << "  </sensors>\n"
      << robot_extra << "</robot>\n";
  std::ofstream(dir / "sensors.xml") << "<?xml version=\"1.0\" ?>\n<sensors>\n"
                                     << scene_sensors << "</sensors>\n";
  std::ofstream(dir / "scene.xml")
      << "<?xml version=\"1.0\" ?>\n<scene>\n  <robot>\n    <ID name='bot'/>\n"
         "    <body file='bot.xml'/>\n  </robot>\n  <obstacles file='room.xml'/>\n"
      << (scene_sensors.empty() ? "" : "  <sensors file='sensors.xml'/>\n") << "</scene>\n";
  return dir;
}

SimulationOptions options(std::uint64_t seed = 1) {
  SimulationOptions o;
  o.seed = seed;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

// --- the analytic room, written independently of the plugin ----------------------------------

/// R = Rx(x)·Ry(y)·Rz(z), degrees (the sensor mount's rot_deg).
Mat3 rotation_deg(const Vec3& deg) {
  const double cx = std::cos(deg.x * kDeg), sx = std::sin(deg.x * kDeg);
  const double cy = std::cos(deg.y * kDeg), sy = std::sin(deg.y * kDeg);
  const double cz = std::cos(deg.z * kDeg), sz = std::sin(deg.z * kDeg);
  Mat3 rx, ry, rz;
  rx.m[1][1] = cx, rx.m[1][2] = -sx, rx.m[2][1] = sx, rx.m[2][2] = cx;
  ry.m[0][0] = cy, ry.m[0][2] = sy, ry.m[2][0] = -sy, ry.m[2][2] = cy;
  rz.m[0][0] = cz, rz.m[0][1] = -sz, rz.m[1][0] = sz, rz.m[1][1] = cz;
  return rx * ry * rz;
}

/// The unit direction of elevation `el` and azimuth `az` (degrees) in the sensor frame.
Vec3 direction(double el_deg, double az_deg) {
  return {std::cos(el_deg * kDeg) * std::cos(az_deg * kDeg),
          std::cos(el_deg * kDeg) * std::sin(az_deg * kDeg), std::sin(el_deg * kDeg)};
}

/// Distance from `o` (inside the room) along the unit `d` to the nearest of its six planes.
double room_distance(const Vec3& o, const Vec3& d) {
  double t = std::numeric_limits<double>::infinity();
  auto plane = [&](double dc, double oc, double lo, double hi) {
    if (dc > 0) t = std::min(t, (hi - oc) / dc);
    if (dc < 0) t = std::min(t, (lo - oc) / dc);
  };
  plane(d.x, o.x, -kHalfX, kHalfX);
  plane(d.y, o.y, -kHalfY, kHalfY);
  plane(d.z, o.z, 0, kHeight);
  return t;
}

float pixel(const Image& im, int x, int y, int k = 0) {
  float v;
  std::memcpy(&v, im.row(y) + (x * (im.format == PixelFormat::xyz_float32 ? 3 : 1) + k) * 4,
              sizeof v);
  return v;
}

/// The room lidar's expected range at pixel (x, y) of its 16 × 1 800 image.
struct RoomGeometry {
  Vec3 origin = kBoxCentre + kMount;  // the box does not turn: the mount is in world axes
  Mat3 rotation = rotation_deg(kRotDeg);
  static double elevation(int y) { return -25 + 40.0 * (15 - y) / 15; }  // row 0 the highest
  static double azimuth(int x) { return -180 + 360.0 * x / 1800; }
  double range(int x, int y) const {
    return room_distance(origin, rotation * direction(elevation(y), azimuth(x)));
  }
};

bool same_bytes(const Image& a, const Image& b) {
  return a.size_bytes() == b.size_bytes() && std::memcmp(a.data, b.data, a.size_bytes()) == 0;
}

// --- tests -----------------------------------------------------------------------------------

TEST(Lidar3D, A16By1800ScanOfABoxRoomMatchesTheRayPlaneDistancesWithin1mm) {
  // A world-fixed twin at the same place and turn sees the robot's box, which the robot's
  // lidar skips.
  std::string twin = room_lidar();
  twin.replace(twin.find("lidar'/>"), 8, "twin'/>");
  twin.replace(twin.find("<solid id='base'/>"), 18, "");
  twin.replace(twin.find("x='0' y='0' z='0.15'"), 20, "x='0.7' y='-0.4' z='1.25'");
  auto sim = Simulation::load(write_scene("room", room_lidar(), twin), options());
  const auto t0 = std::chrono::steady_clock::now();
  sim->step(1);  // the first scan, at tick 0
  const double step_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const Image& range = sim->image("robots/bot/sensors/lidar/range");
  const Image& points = sim->image("robots/bot/sensors/lidar/points");
  ASSERT_EQ(range.width_px, 1800);
  ASSERT_EQ(range.height_px, 16);
  ASSERT_EQ(range.format, PixelFormat::float32);
  ASSERT_EQ(points.width_px, 1800);
  ASSERT_EQ(points.height_px, 16);
  ASSERT_EQ(points.format, PixelFormat::xyz_float32);
  EXPECT_EQ(range.frame, 1u);
  const RoomGeometry room;
  double worst = 0, worst_point = 0, nearest = std::numeric_limits<double>::infinity();
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 1800; ++x) {
      const double expected = room.range(x, y);  // every ray meets the closed room
      const double r = pixel(range, x, y);
      ASSERT_TRUE(std::isfinite(r)) << x << ", " << y;
      worst = std::max(worst, std::abs(r - expected));
      nearest = std::min(nearest, expected);
      // The point is the range along the ray's direction in the sensor frame.
      const Vec3 d = direction(RoomGeometry::elevation(y), RoomGeometry::azimuth(x));
      for (int k = 0; k < 3; ++k) {
        const double c = k == 0 ? d.x : k == 1 ? d.y : d.z;
        worst_point = std::max(worst_point, std::abs(pixel(points, x, y, k) - r * c));
      }
    }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst, 1e-5);  // in fact exact to the float's rounding
  EXPECT_LT(worst_point, 1e-5);
  // The rays skip the robot's own box, 5 cm under the lidar (the lowest channels cross its top).
  EXPECT_EQ(sim->signal("robots/bot/sensors/lidar/hits"), 16 * 1800);
  EXPECT_NEAR(sim->signal("robots/bot/sensors/lidar/nearest"), nearest, 1e-5);
  const Image& twin_range = sim->image("sensors/twin/range");
  int on_the_box = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 1800; ++x)
      on_the_box += pixel(twin_range, x, y) < 0.3f;
  EXPECT_GT(on_the_box, 1800);  // the lowest channels, within 0.3 m
  std::printf(
      "lidar3d 16 x 1800 room scan: max range error %.2g m, max point error %.2g m, "
      "nearest %.4f m; first step with both scans %.1f ms (wall time); the twin sees the "
      "robot's box on %d rays\n",
      worst, worst_point, nearest, step_ms, on_the_box);
}

TEST(Lidar3D, ConventionsAzimuthCounterClockwiseFromPlusXRowZeroHighestRangeLimits) {
  // World-fixed at (-1, 0.5, 1.5), unturned: the walls are 2 m (-X), 2.5 m (-Y), 4 m (+X) and
  // 1.5 m (+Y) away, the floor and the ceiling 1.5 m.
  const std::string sensors =
      "<lidar3d>\n  <ID value='cross'/>\n  <pos x='-1' y='0.5' z='1.5'/>\n"
      "  <channels count='3' lowest='-45' highest='45'/>\n"
      "  <azimuth steps='4' start='-180' stop='180'/>\n"  // a full turn: -180, -90, 0, 90
      "  <range min='1.8' max='3'/>\n</lidar3d>\n"
      "<lidar3d>\n  <ID value='fan'/>\n  <pos x='-1' y='0.5' z='1.5'/>\n"
      "  <channels count='1' lowest='0' highest='0'/>\n"
      "  <azimuth steps='3' start='-90' stop='90'/>\n</lidar3d>\n";  // a span: both ends
  auto sim = Simulation::load(write_scene("conventions", "", sensors), options());
  sim->step(1);
  const Image& r = sim->image("sensors/cross/range");
  const Image& p = sim->image("sensors/cross/points");
  ASSERT_EQ(r.width_px, 4);
  ASSERT_EQ(r.height_px, 3);
  const float inf = std::numeric_limits<float>::infinity();
  // Row 1 (elevation 0): -X at 2 m, -Y at 2.5 m, +X past the 3 m maximum, +Y nearer than the
  // 1.8 m minimum.
  EXPECT_NEAR(pixel(r, 0, 1), 2.0, 1e-6);
  EXPECT_NEAR(pixel(r, 1, 1), 2.5, 1e-6);
  EXPECT_EQ(pixel(r, 2, 1), inf);
  EXPECT_EQ(pixel(r, 3, 1), inf);
  EXPECT_TRUE(std::isnan(pixel(p, 2, 1, 0)) && std::isnan(pixel(p, 2, 1, 1)) &&
              std::isnan(pixel(p, 2, 1, 2)));
  EXPECT_NEAR(pixel(p, 1, 1, 0), 0.0, 1e-6);  // the point (0, -2.5, 0), sensor frame
  EXPECT_NEAR(pixel(p, 1, 1, 1), -2.5, 1e-6);
  EXPECT_NEAR(pixel(p, 1, 1, 2), 0.0, 1e-6);
  // Row 0 is the highest channel (+45°): toward +X it meets the ceiling 1.5 m up at 1.5·√2.
  EXPECT_NEAR(pixel(r, 2, 0), 1.5 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(pixel(p, 2, 0, 0), 1.5, 1e-6);
  EXPECT_NEAR(pixel(p, 2, 0, 2), 1.5, 1e-6);
  // Row 2 (-45°) toward +X meets the floor as far.
  EXPECT_NEAR(pixel(r, 2, 2), 1.5 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(pixel(p, 2, 2, 2), -1.5, 1e-6);
  int hits = 0;
  double nearest = inf;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const double d = room_distance({-1, 0.5, 1.5}, direction(45 - 45 * y, -180 + 90 * x));
      const bool seen = d >= 1.8 && d <= 3;
      EXPECT_EQ(std::isfinite(pixel(r, x, y)), seen) << x << ", " << y;
      if (seen) {
        EXPECT_NEAR(pixel(r, x, y), d, 1e-6) << x << ", " << y;
        ++hits;
        nearest = std::min(nearest, d);
      }
    }
  EXPECT_EQ(sim->signal("sensors/cross/hits"), hits);
  EXPECT_NEAR(sim->signal("sensors/cross/nearest"), nearest, 1e-9);
  // A partial span includes both ends: -90°, 0°, +90°.
  const Image& f = sim->image("sensors/fan/range");
  ASSERT_EQ(f.width_px, 3);
  EXPECT_NEAR(pixel(f, 0, 0), 2.5, 1e-6);
  EXPECT_NEAR(pixel(f, 1, 0), 4.0, 1e-6);
  EXPECT_NEAR(pixel(f, 2, 0), 1.5, 1e-6);
}

TEST(Lidar3D, NoiseHasItsMeanAndStdevAndTheSameSeedGivesTheSameImages) {
  const fs::path dir = write_scene("noise", room_lidar("  <noise stdev='0.01'/>\n"));
  auto a = Simulation::load(dir, options(5));
  a->step(1);
  const Image& range = a->image("robots/bot/sensors/lidar/range");
  const RoomGeometry room;
  double sum = 0, sum2 = 0;
  const int n = 16 * 1800;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 1800; ++x) {
      const double e = pixel(range, x, y) - room.range(x, y);
      sum += e;
      sum2 += e * e;
    }
  const double mean = sum / n, stdev = std::sqrt((sum2 - n * mean * mean) / (n - 1));
  EXPECT_NEAR(mean, 0.0, 4 * 0.01 / std::sqrt(n));  // 4 standard errors: 2.4e-4 m
  EXPECT_NEAR(stdev / 0.01, 1.0, 0.03);             // its own standard error is 0.4 %
  std::printf(
      "lidar3d noise stdev 0.01 m over %d rays: mean error %.2e m, stdev %.5f m "
      "(%+.2f %%)\n",
      n, mean, stdev, 100 * (stdev / 0.01 - 1));
  // The same seed: byte-identical images; another seed: other noise on every pixel.
  auto b = Simulation::load(dir, options(5));
  auto c = Simulation::load(dir, options(6));
  b->step(1);
  c->step(1);
  for (const char* name : {"robots/bot/sensors/lidar/range", "robots/bot/sensors/lidar/points"})
    EXPECT_TRUE(same_bytes(a->image(name), b->image(name))) << name;
  const Image& other = c->image("robots/bot/sensors/lidar/range");
  int same = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 1800; ++x)
      same += pixel(range, x, y) == pixel(other, x, y);
  EXPECT_LT(same, n / 100);
  // reset() replays the same noise.
  std::vector<std::uint8_t> first(range.data, range.data + range.size_bytes());
  a->step(10);
  a->reset();
  a->step(1);
  EXPECT_EQ(std::memcmp(first.data(), range.data, first.size()), 0);
}

TEST(Lidar3D, TheFrameCounterAdvancesOncePerPeriod) {
  auto sim =
      Simulation::load(write_scene("period", room_lidar("  <period value='0.02'/>\n")), options());
  const auto period_ticks = std::llround(0.02 / sim->tick_s());
  ASSERT_GE(period_ticks, 2);
  const Image& range = sim->image("robots/bot/sensors/lidar/range");
  EXPECT_EQ(range.frame, 0u);  // no scan before the first tick
  for (std::int64_t tick = 0; tick < 5 * period_ticks; ++tick) {
    sim->step(1);
    // Scans at ticks 0, P, 2P...: after tick t, 1 + floor(t / P) frames.
    ASSERT_EQ(range.frame, static_cast<std::uint64_t>(1 + tick / period_ticks)) << tick;
    EXPECT_NEAR(range.time_s,
                static_cast<double>(tick / period_ticks * period_ticks) * sim->tick_s(), 1e-12);
    EXPECT_EQ(sim->image("robots/bot/sensors/lidar/points").frame, range.frame);
  }
  sim->reset();
  EXPECT_EQ(range.frame, 0u);
}

TEST(Lidar3D, APluginPlacementReadsTheSameChildrenAndScansTheSame) {
  // <plugin kind='lidar3d'> in the robot file: the same children, read by the plugin itself.
  std::string plugin = room_lidar();
  plugin.replace(0, std::string("<lidar3d>\n  <ID value='lidar'/>\n").size(),
                 "<plugin kind='lidar3d' id='plug'>\n");
  plugin.replace(plugin.rfind("</lidar3d>"), 10, "</plugin>");
  auto sim = Simulation::load(write_scene("plugin", room_lidar(), "", plugin), options());
  for (const std::string& w : sim->warnings())
    ADD_FAILURE() << w;  // every attribute read, none ignored
  sim->step(1);
  for (const char* image : {"range", "points"})
    EXPECT_TRUE(same_bytes(sim->image(std::string("robots/bot/sensors/lidar/") + image),
                           sim->image(std::string("robots/bot/sensors/plug/") + image)))
        << image;
}

/// The message of loading the room with the lidar given `children` instead of its defaults.
std::string load_error(const std::string& name, const std::string& children) {
  const fs::path dir =
      write_scene(name, "<lidar3d>\n  <ID value='lidar'/>\n" + children + "</lidar3d>\n");
  try {
    Simulation::load(dir, options());
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Lidar3D, BadParametersAreErrorsNamingTheElementAttributeAndValue) {
  const auto at = [](const char* element) {
    return HasSubstr(std::string("bot.xml: robot/sensors/lidar3d/") + element);
  };
  EXPECT_THAT(load_error("count0", "<channels count='0'/>"),
              AllOf(at("channels@count"), HasSubstr("must be an integer from 1 to 16384, got 0")));
  EXPECT_THAT(load_error("inverted", "<channels lowest='20' highest='10'/>"),
              AllOf(at("channels@lowest"), HasSubstr("must be below highest (10 degrees)"),
                    HasSubstr("got 20")));
  EXPECT_THAT(load_error("steep", "<channels highest='95'/>"),
              AllOf(at("channels@highest"), HasSubstr("must be in -90..90 degrees, got 95")));
  EXPECT_THAT(load_error("steps0", "<azimuth steps='0'/>"),
              AllOf(at("azimuth@steps"), HasSubstr("must be an integer from 1 to 16384, got 0")));
  EXPECT_THAT(load_error("wide", "<azimuth steps='20000'/>"),
              AllOf(at("azimuth@steps"), HasSubstr("got 20000")));
  EXPECT_THAT(load_error("pixels", "<channels count='8192'/>\n<azimuth steps='16384'/>"),
              AllOf(at("azimuth@steps"), HasSubstr("134217728 rays"),
                    HasSubstr("past the most pixels of an image (67108864)")));
  EXPECT_THAT(load_error("turns", "<azimuth start='0' stop='400'/>"),
              AllOf(at("azimuth@stop"), HasSubstr("by at most 360 degrees, got 400")));
  EXPECT_THAT(load_error("backwards", "<azimuth start='10' stop='-10'/>"),
              AllOf(at("azimuth@stop"), HasSubstr("must be above start (10 degrees)")));
  EXPECT_THAT(load_error("maxmin", "<range min='5' max='2'/>"),
              AllOf(at("range@max"), HasSubstr("must be above min (5 m), got 2")));
  EXPECT_THAT(load_error("maxzero", "<range min='0' max='0'/>"),
              AllOf(at("range@max"), HasSubstr("got 0")));
  EXPECT_THAT(load_error("negmin", "<range min='-1'/>"),
              AllOf(at("range@min"), HasSubstr("must be >= 0 m, got -1")));
  EXPECT_THAT(load_error("noise", "<noise stdev='-0.1'/>"),
              AllOf(at("noise@stdev"), HasSubstr("-0.1")));
}

}  // namespace
}  // namespace s2sim
