// The `spraygun` sensor on a plate held still under it (tests/common/spray_scene.hpp): the
// footprint, coverage and thicknesses the model of docs/models/sensors.md ("Spray painting")
// gives, occlusion, reset and snapshots, a moving target, and located errors.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include "common/spray_scene.hpp"
#include "common/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using test::SprayScene;
using ::testing::HasSubstr;

SimulationOptions options() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

std::unique_ptr<Simulation> load(const std::string& name, const SprayScene& s) {
  return Simulation::load(test::write_spray_scene(test::process_temp_dir() / name, s), options());
}

/// Every triangle's thickness of the gun's paint, and its centre in the plate's frame.
struct Paint {
  std::vector<double> t;
  std::vector<double> x, y;
};
Paint paint(const Simulation& sim, const SprayScene& s) {
  Paint p;
  const double h = s.side_m / s.cells;
  for (int j = 0; j < s.cells; ++j)
    for (int i = 0; i < s.cells; ++i)
      for (int half = 0; half < 2;
           ++half) {  // (i,j),(i+1,j),(i+1,j+1) then (i,j),(i+1,j+1),(i,j+1)
        const auto k = static_cast<int>(p.t.size());
        p.t.push_back(sim.signal("sensors/gun/paint/0/" + std::to_string(k)));
        p.x.push_back(-s.side_m / 2 + (i + (half == 0 ? 2.0 : 1.0) / 3) * h);
        p.y.push_back(-s.side_m / 2 + (j + (half == 0 ? 1.0 : 2.0) / 3) * h);
      }
  return p;
}

/// The nozzle's height above the plate's top face as the plate stands (it settles into the
/// floor by a fraction of a millimetre).
double height_now(const Simulation& sim, const SprayScene& s) {
  return 0.01 + s.height_m - (sim.body_pose(1).position.z + 0.005);  // body 1: the plate
}

/// W = 2π ∫₀^θmax exp(−θ²/2σ²) sin θ dθ by the trapezoidal rule, independently of the plugin.
double cone_weight(double theta_max, double sigma) {
  const int n = 100000;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = theta_max * i / n;
    sum += (i == 0 || i == n ? 0.5 : 1.0) * std::exp(-t * t / (2 * sigma * sigma)) * std::sin(t);
  }
  return 2 * kPi * sum * theta_max / n;
}

/// The model's thickness on the plate at radius rho from the point under the nozzle after
/// `time_s`: Q·T·exp(−θ²/2σ²)·cos³θ / (W·h²), θ = atan(rho/h).
double expected_thickness(const SprayScene& s, double h, double rho, double time_s) {
  const double sigma = s.max_angle_rad / 2;
  const double theta = std::atan(rho / h);
  return s.rate_m3_s * time_s * std::exp(-theta * theta / (2 * sigma * sigma)) *
         std::pow(std::cos(theta), 3) / (cone_weight(s.max_angle_rad, sigma) * h * h);
}

/// The triangle whose centre is nearest (x, y).
std::size_t nearest(const Paint& p, double x, double y) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < p.t.size(); ++k)
    if (std::hypot(p.x[k] - x, p.y[k] - y) < std::hypot(p.x[best] - x, p.y[best] - y)) best = k;
  return best;
}

TEST(SprayGun, HeldStillOverAPlatePaintsTheConesDiskWithTheModelsProfile) {
  const SprayScene s;  // 0.4 m plate, 20 000 triangles, nozzle 0.3 m up, 0.3 rad cone
  auto sim = load("still", s);
  sim->run_until(1.0);  // 100 coats at the gun's 10 ms period: 1 s of spray
  const Paint p = paint(*sim, s);
  const double cell_area = (s.side_m / s.cells) * (s.side_m / s.cells) / 2;
  double sum = 0, volume = 0;
  int painted = 0;
  double outside = 0;  // paint found outside the footprint's disk
  const double h = height_now(*sim, s);
  const double radius = h * std::tan(s.max_angle_rad);
  for (std::size_t k = 0; k < p.t.size(); ++k) {
    sum += p.t[k];
    volume += p.t[k] * cell_area;
    if (p.t[k] > 0) ++painted;
    if (std::hypot(p.x[k], p.y[k]) > radius + 1e-9) outside += p.t[k];
  }
  const double n = static_cast<double>(p.t.size());
  const double disk = kPi * radius * radius;
  // Footprint: the disk of radius h·tan θmax, nothing outside it.
  EXPECT_EQ(outside, 0);
  EXPECT_NEAR(painted / n, disk / (s.side_m * s.side_m), 0.05 * disk / (s.side_m * s.side_m));
  // The whole flow lands: the volume is Q·T, the mean thickness Q·T/L², over the painted
  // triangles Q·T/(π R²).
  EXPECT_NEAR(volume, s.rate_m3_s * 1.0, 0.01 * s.rate_m3_s);
  EXPECT_NEAR(sim->signal("sensors/gun/volume"), volume, 1e-6 * volume);
  EXPECT_NEAR(sum / n, s.rate_m3_s / (s.side_m * s.side_m),
              0.05 * s.rate_m3_s / (s.side_m * s.side_m));
  EXPECT_NEAR(sum / painted, s.rate_m3_s / disk, 0.05 * s.rate_m3_s / disk);
  // The profile: under the nozzle, at half the radius, near the rim.
  for (const double rho : {0.0, radius / 2, 0.9 * radius}) {
    const std::size_t k = nearest(p, rho, 0);
    const double r = std::hypot(p.x[k], p.y[k]);
    EXPECT_NEAR(p.t[k], expected_thickness(s, h, r, 1.0), 0.05 * expected_thickness(s, h, r, 1.0))
        << "at rho " << r;
  }
  const std::size_t c = nearest(p, 0, 0);
  std::printf(
      "spray: coverage %.5f (model %.5f), mean %.5g m (model %.5g), painted mean %.5g m "
      "(model %.5g), centre %.5g m (model %.5g), volume %.6g m3 (Q T %.6g)\n",
      painted / n, disk / (s.side_m * s.side_m), sum / n, s.rate_m3_s / (s.side_m * s.side_m),
      sum / painted, s.rate_m3_s / disk, p.t[c],
      expected_thickness(s, h, std::hypot(p.x[c], p.y[c]), 1.0), volume, s.rate_m3_s);
  RecordProperty("coverage", std::to_string(painted / n));
  RecordProperty("mean_thickness_m", std::to_string(sum / n));
  RecordProperty("painted_mean_thickness_m", std::to_string(sum / painted));
  RecordProperty("centre_thickness_m", std::to_string(p.t[nearest(p, 0, 0)]));
}

TEST(SprayGun, OffItPaintsNothingAndMinDistIsTheNearestTriangle) {
  SprayScene s;
  s.on = false;
  auto sim = load("off", s);
  sim->run_until(0.2);
  EXPECT_EQ(sim->signal("sensors/gun/volume"), 0);
  const Paint p = paint(*sim, s);
  const std::size_t k = nearest(p, 0, 0);
  EXPECT_NEAR(sim->signal("sensors/gun/min_dist"),
              std::hypot(height_now(*sim, s), std::hypot(p.x[k], p.y[k])), 1e-6);
  sim->set_input("sensors/gun/on", 1);  // SetSprayGunOn's input
  sim->run_until(0.4);
  EXPECT_GT(sim->signal("sensors/gun/volume"), 0);
  EXPECT_DOUBLE_EQ(sim->signal("sensors/gun/paint_color/r"), 1);  // red without the element
}

TEST(SprayGun, AnOccludingSheetKeepsThePaintOffWhatItShadows) {
  SprayScene s;
  s.blocker = true;  // a sheet halfway up over x in [0.01, 0.31]: its shadow is x > 0.02
  s.occlusion = true;
  auto occluded = load("occluded", s);
  occluded->run_until(0.5);
  s.occlusion = false;
  auto through = load("through", s);
  through->run_until(0.5);
  const Paint a = paint(*occluded, s), b = paint(*through, s);
  double shadow_a = 0, shadow_b = 0, lit_a = 0, lit_b = 0;
  for (std::size_t k = 0; k < a.t.size(); ++k) {
    if (a.x[k] > 0.03) {
      shadow_a += a.t[k];
      shadow_b += b.t[k];
    } else if (a.x[k] < 0.01) {
      lit_a += a.t[k];
      lit_b += b.t[k];
    }
  }
  EXPECT_EQ(shadow_a, 0);
  EXPECT_GT(shadow_b, 0.15 * (lit_b + shadow_b));  // without occlusion it paints through
  EXPECT_DOUBLE_EQ(lit_a, lit_b);                  // the lit side is the same either way
}

TEST(SprayGun, ResetSnapshotsAndTheResetInputAreExact) {
  const SprayScene s;
  auto sim = load("reset", s);
  sim->run_until(0.3);
  const auto snap = sim->save();
  sim->run_until(0.6);
  const double v = sim->signal("sensors/gun/volume");
  const std::vector<double> at_06 = paint(*sim, s).t;
  sim->restore(snap);
  sim->run_until(0.6);
  EXPECT_EQ(sim->signal("sensors/gun/volume"), v);
  EXPECT_EQ(paint(*sim, s).t, at_06);
  sim->reset();
  EXPECT_EQ(sim->signal("sensors/gun/volume"), 0);
  for (double t : paint(*sim, s).t)
    ASSERT_EQ(t, 0);
  sim->run_until(0.6);
  EXPECT_EQ(paint(*sim, s).t, at_06) << "a reset starts the same run again";
  // ResetPaintTargetPaint's input: the gun clears the target at its next update.
  sim->set_input("sensors/gun/on", 0);
  sim->set_input("paint_targets/0/resets", 1);
  sim->run_until(0.65);
  EXPECT_EQ(sim->signal("sensors/gun/volume"), 0);
  EXPECT_EQ(sim->signal("sensors/gun/paint/0/resets"), 1);
}

TEST(SprayGun, PaintStaysOnTheTrianglesItLandedOnWhenThePlateMoves) {
  SprayScene s;
  s.plate_x_m = 0.1;  // the nozzle is over the plate's x = -0.1
  auto sim = load("moving", s);
  sim->run_until(0.3);
  auto centroid = [&](const Paint& p) {
    double w = 0, x = 0;
    for (std::size_t k = 0; k < p.t.size(); ++k) {
      w += p.t[k];
      x += p.t[k] * p.x[k];
    }
    return x / w;
  };
  const Paint first = paint(*sim, s);
  EXPECT_NEAR(centroid(first), -0.1, 2e-3);  // in the plate's frame
  // Carried to x = -0.1: the next coat lands on its x = +0.1, the first stays where it was.
  const int plate = 1;  // body 0 is the world
  Pose pose = sim->body_pose(plate);
  pose.position.x = -0.1;
  sim->set_input("sensors/gun/on", 0);
  sim->place_body(plate, pose);
  sim->run_until(0.35);
  const Paint moved = paint(*sim, s);
  EXPECT_EQ(moved.t, first.t);
  sim->set_input("sensors/gun/on", 1);
  sim->run_until(0.65);
  Paint second = paint(*sim, s);
  for (std::size_t k = 0; k < second.t.size(); ++k)
    second.t[k] -= first.t[k];
  EXPECT_NEAR(centroid(second), 0.1, 2e-3);
}

TEST(SprayGun, ABadParameterIsAnErrorNamingFileElementAttributeAndValue) {
  struct Case {
    const char* from;
    const char* to;
    const char* says;
  };
  const Case cases[] = {
      {"<paint_rate value='1e-06'/>", "<paint_rate value='-1'/>", "paint_rate@value"},
      {"<paint_max_angle value='0.3'/>", "<paint_max_angle value='2'/>", "paint_max_angle@value"},
      {"<paint_occlusion value='0'/>", "<paint_occlusion value='maybe'/>", "paint_occlusion@value"},
      {"<paint_occlusion value='0'/>", "<paint_color_rgb r='300'/>", "paint_color_rgb@r"}};
  for (const Case& c : cases) {
    const fs::path dir = test::write_spray_scene(
        test::process_temp_dir() / ("bad" + std::to_string(&c - cases)), SprayScene{});
    std::ifstream in(dir / "sensors.xml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, std::string(c.from).size(), c.to);
    std::ofstream(dir / "sensors.xml") << text;
    try {
      Simulation::load(dir, options());
      ADD_FAILURE() << "expected an error for " << c.to;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("sensors.xml")) << c.to;
      EXPECT_THAT(e.what(), HasSubstr("spraygun")) << c.to;
      EXPECT_THAT(e.what(), HasSubstr(c.says)) << c.to;
    }
  }
}

TEST(SprayGun, WithoutAPaintingTargetItWarnsAndPaintsNothing) {
  const fs::path dir = test::write_spray_scene(test::process_temp_dir() / "bare", SprayScene{});
  std::ofstream(dir / "things.xml") << "<?xml version='1.0' ?>\n<things/>\n";
  auto sim = Simulation::load(dir, options());
  bool warned = false;
  for (const std::string& w : sim->warnings())
    warned = warned || w.find("no painting target") != std::string::npos;
  EXPECT_TRUE(warned);
  sim->run_until(0.1);
  EXPECT_EQ(sim->signal("sensors/gun/min_dist"), -1);
}

}  // namespace
}  // namespace s2sim
