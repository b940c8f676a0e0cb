// Speculative contact (docs/models/contact.md, "Speculative contact"): fast landings at a 1 ms
// step without substeps stay shallow, and impacts still rebound at the surfaces' restitution.
#include "contact/contact_world.hpp"
#include "contact_runner.hpp"
#include "model/multibody.hpp"
#include "scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace s2sim::contact {
namespace {

constexpr double kG = kGravity_m_s2;

using Runner = test::ContactRunner;

void set_surface(scene::Body& b, double mu, double bounce) {
  for (auto& g : b.geoms) {
    g.surface.explicit_surface = true;
    g.surface.mu = mu;
    g.surface.bounce = bounce;
  }
}

struct Landing {
  double rebound_m = 0;   ///< highest the dropped body's bottom rises after the impact
  double deepest_m = 0;   ///< deepest contact over the run
  double touched_s = -1;  ///< when the first contact was reported
};

/// Drops `body` (scene body `dropped`) from rest and follows it through its first impact:
/// the rebound is the height its lowest point reaches once it moves up again, measured from
/// `surface_z` (where it rests).
Landing drop(const scene::Scene& s, int dropped, double half_height, double surface_z,
             double seconds) {
  Runner run(s);
  Landing out;
  bool rising = false;
  const auto body = static_cast<std::size_t>(dropped + 1);
  for (int n = 0; n < static_cast<int>(seconds * 1e3); ++n) {
    run.step();
    out.deepest_m = std::max(out.deepest_m, run.deepest_m());
    if (out.touched_s < 0 && *run.contacts.contact_count() > 0) out.touched_s = n * 1e-3;
    const double vz = run.twists[body].linear_m_s.z;
    if (out.touched_s >= 0 && !rising && vz >= 0) rising = true;
    if (rising) {
      out.rebound_m = std::max(out.rebound_m, run.poses[body].position.z - half_height - surface_z);
      if (vz < -1e-3 && out.rebound_m > 1e-4) break;  // past the apex
    }
  }
  return out;
}

/// A fixed cube of side `size` centred at `center`.
scene::Geom block(const Vec3& center, double size) {
  scene::Geom g;
  g.id = "block";
  g.shape.type = scene::ShapeType::box;
  g.shape.size_m = {size, size, size};
  g.pose = {center, {}};
  return g;
}

/// A 0.2 kg ball of 5 cm radius dropped from `height` onto the ground.
Landing ball_on_ground(double height, double e) {
  const double radius = 0.05;
  scene::Scene s;
  s.bodies.push_back(test::sphere("ball", 0.2, radius, {0, 0, radius + height}));
  set_surface(s.bodies[0], 0.5, e);
  return drop(s, 0, radius, 0, std::sqrt(2 * height / kG) + 2.5);
}

TEST(SpeculativeContact, BallsReboundToRestitutionSquaredTimesTheDropHeight) {
  // The rebound against e²·h over drop heights and restitutions; plastic balls stay down.
  std::printf("| drop m | e | rebound m | e²·h m | error | deepest mm |\n");
  for (double e : {0.0, 0.2, 0.5, 0.8}) {
    for (double height : {0.05, 0.2, 1.0, 3.0}) {
      const Landing l = ball_on_ground(height, e);
      const double expected = e * e * height;
      std::printf("| %.2f | %.1f | %.5f | %.5f | %+.1f %% | %.3f |\n", height, e, l.rebound_m,
                  expected, expected > 0 ? 100 * (l.rebound_m / expected - 1) : 0.0,
                  l.deepest_m * 1e3);
      const std::string label = "e " + std::to_string(e) + ", h " + std::to_string(height);
      if (e == 0) {
        EXPECT_LT(l.rebound_m, 0.005 * height + 1e-4) << label;
      } else {
        EXPECT_NEAR(l.rebound_m, expected, 0.05 * expected + 2e-4) << label;
      }
      EXPECT_LT(l.deepest_m, 2e-3) << label;
    }
  }
}

TEST(SpeculativeContact, FastLandingsOnTheGroundAndOnABoxStayWithinTwoMillimetres) {
  // Dropped from 0.5 m: 3.1 m/s at the surface, 3.1 mm per 1 ms step.
  const double drop_m = 0.5, size = 0.1;
  {
    scene::Scene s;  // a ball onto the ground
    s.bodies.push_back(test::sphere("ball", 0.2, 0.05, {0, 0, 0.05 + drop_m}));
    const Landing l = drop(s, 0, 0.05, 0, 1.0);
    RecordProperty("ball_on_ground_mm", std::to_string(l.deepest_m * 1e3));
    EXPECT_GT(l.touched_s, 0.0);
    EXPECT_LT(l.deepest_m, 2e-3);
    EXPECT_LT(l.rebound_m, 1e-3);  // no bounce given: plastic
  }
  {
    scene::Scene s;  // a box onto the ground, turned so that it lands on an edge
    s.bodies.push_back(test::box("box", 0.5, {size, size, size}, {0, 0, size / 2 + drop_m},
                                 test::rotation_about({1, 0, 0}, 0.3)));
    const Landing l = drop(s, 0, size / 2, 0, 1.5);
    RecordProperty("box_on_ground_mm", std::to_string(l.deepest_m * 1e3));
    EXPECT_GT(l.touched_s, 0.0);
    EXPECT_LT(l.deepest_m, 2e-3);
  }
  {
    scene::Scene s;  // a box flat onto a fixed box (an obstacle standing on the ground)
    s.obstacles.push_back(block({0, 0, size / 2}, size));
    s.bodies.push_back(
        test::box("above", 0.5, {size, size, size}, {0.01, 0.02, 1.5 * size + drop_m}));
    const Landing l = drop(s, 0, size / 2, size, 1.0);
    RecordProperty("box_on_box_mm", std::to_string(l.deepest_m * 1e3));
    EXPECT_GT(l.touched_s, 0.0);
    EXPECT_LT(l.deepest_m, 2e-3);
    EXPECT_LT(l.rebound_m, 1e-3);
  }
  {
    scene::Scene s;  // a bouncing ball onto a fixed box
    s.obstacles.push_back(block({0, 0, size / 2}, size));
    s.bodies.push_back(test::sphere("ball", 0.2, 0.03, {0.01, 0, size + 0.03 + drop_m}));
    set_surface(s.bodies[0], 0.5, 0.5);
    const Landing l = drop(s, 0, 0.03, size, 1.0);
    RecordProperty("ball_on_box_mm", std::to_string(l.deepest_m * 1e3));
    RecordProperty("ball_on_box_rebound_m", std::to_string(l.rebound_m));
    EXPECT_GT(l.touched_s, 0.0);
    EXPECT_LT(l.deepest_m, 2e-3);
    EXPECT_NEAR(l.rebound_m, 0.25 * drop_m, 0.05 * 0.25 * drop_m);
  }
}

TEST(SpeculativeContact, APointThatWouldNotReachTheSurfaceIsNoContactAndLeavesNoMemory) {
  // A ball released 3 mm above the ground: its first steps find it within its margin (its
  // speed times the step) but far from crossing the gap; no contact is reported until it lands.
  scene::Scene s;
  s.bodies.push_back(test::sphere("ball", 0.2, 0.05, {0, 0, 0.05 + 0.003}));
  Runner run(s);
  // Falling from rest: 3 mm takes 25 ms; the first steps' closing speed is far below gap/h.
  int first_contact = -1;
  for (int n = 0; n < 100 && first_contact < 0; ++n) {
    run.step();
    if (*run.contacts.contact_count() > 0) first_contact = n;
  }
  // Free fall covers 3 mm in 24.7 ms: the first contact is the landing, not before.
  EXPECT_GE(first_contact, 23);
  EXPECT_LE(first_contact, 27);
  EXPECT_LT(run.deepest_m(), 1e-4);
}

}  // namespace
}  // namespace s2sim::contact
