#pragma once
// The fast path (tree_dynamics.cpp, loop_constraints.cpp) against Simbody's realize chain, tick
// by tick from the same state under the same loads (tree_dynamics_test, loop_constraints_test).

#include "common/state_layout.hpp"
#include "model/multibody.hpp"
#include "model_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace s2sim::test {

/// Loads that change every tick and reach every body and axis: sines of incommensurate rates.
inline void load_everywhere(model::Multibody& mb, int tick) {
  Wrench* w = mb.applied_wrenches();
  for (int b = 1; b < mb.body_count(); ++b) {
    const double t = 0.37 * tick + 1.3 * b;
    w[b] = Wrench{{0.05 * std::sin(t), 0.04 * std::cos(1.1 * t), 0.03 * std::sin(0.7 * t)},
                  {2 * std::cos(t), 3 * std::sin(1.3 * t), 1.5 * std::cos(0.9 * t)}};
  }
  // Slowly turning axis loads build speed; fast ones shake it.
  for (std::size_t a = 0; a < mb.axes().size(); ++a)
    mb.applied_axis_forces()[a] = 0.3 * std::sin(0.004 * tick + static_cast<double>(a)) +
                                  0.1 * std::sin(0.5 * tick + static_cast<double>(a));
}

/// What the fast path may differ from Simbody by in one tick.
struct FastPathTolerance {
  double pose = 1e-14;           // position (m) plus two rotation columns
  double axis_velocity = 1e-12;  // relative to 1 + |v|
};

/// One scene twice, on the fast path and on Simbody's realize chain, and the copy of the first
/// one's state into the second that starts each compared tick.
struct FastAndSimbody {
  explicit FastAndSimbody(const scene::Scene& s) : fast(s), simbody(s) {
    simbody.mb.choose_dynamics(model::DynamicsChoice::simbody);
    fast.mb.declare_state(fast_layout);
    simbody.mb.declare_state(simbody_layout);
  }
  /// Simbody's run takes the fast path's state.
  void sync() {
    state.clear();
    fast_layout.save(state);
    simbody_layout.restore(simbody_layout.id(), simbody_layout.entries(), state);
    simbody.mb.restored();
  }
  Runner fast, simbody;
  common::StateLayout fast_layout, simbody_layout;
  std::vector<double> state;
};

/// Per tick: Simbody takes the fast path's state, both step under the same loads (`load`,
/// then `extra` if given), and the change of every body's velocity over the tick
/// (h·acceleration) is compared. Returns the worst difference relative to that change, once
/// the rounding of adding the change to the velocity (a few ulps of the velocity) is taken off.
inline double worst_relative_difference(
    const scene::Scene& s, int ticks, FastPathTolerance tolerance = {},
    const std::function<void(model::Multibody&, int)>& extra = nullptr) {
  FastAndSimbody runs(s);
  Runner &fast = runs.fast, &simbody = runs.simbody;
  EXPECT_TRUE(fast.mb.uses_tree_fast_path());
  EXPECT_FALSE(simbody.mb.uses_tree_fast_path());
  double worst = 0, fastest = 0;
  for (int tick = 0; tick < ticks; ++tick) {
    runs.sync();
    fast.read();
    const std::vector<Twist> before = fast.twists;
    for (Runner* r : {&fast, &simbody}) {
      load_everywhere(r->mb, tick);
      if (extra) extra(r->mb, tick);
    }
    fast.step();
    simbody.step();
    for (int b = 1; b < fast.mb.body_count(); ++b) {
      const Twist& f = fast.twists[b];
      const Twist& g = simbody.twists[b];
      const double change = std::max(norm(f.angular_rad_s - before[b].angular_rad_s),
                                     norm(f.linear_m_s - before[b].linear_m_s));
      const double differs =
          std::max(norm(f.angular_rad_s - g.angular_rad_s), norm(f.linear_m_s - g.linear_m_s));
      const double pose_differs =
          norm(fast.poses[b].position - simbody.poses[b].position) +
          norm(fast.poses[b].rotation.column(0) - simbody.poses[b].rotation.column(0)) +
          norm(fast.poses[b].rotation.column(1) - simbody.poses[b].rotation.column(1));
      EXPECT_LE(pose_differs, tolerance.pose) << "body " << b << " tick " << tick;
      const double speed = std::max(norm(f.angular_rad_s), norm(f.linear_m_s));
      const double rounding = 8 * std::numeric_limits<double>::epsilon() * speed;
      if (change > 0) worst = std::max(worst, std::max(0.0, differs - rounding) / change);
      fastest = std::max(fastest, norm(f.angular_rad_s));
    }
    for (std::size_t a = 0; a < fast.vel.size(); ++a)
      EXPECT_NEAR(fast.vel[a], simbody.vel[a],
                  tolerance.axis_velocity * (1 + std::abs(fast.vel[a])))
          << fast.mb.axes()[a].name << " tick " << tick;
  }
  EXPECT_GT(fastest, 1.0) << "the bodies must spin for the velocity-product terms to count";
  return worst;
}

}  // namespace s2sim::test
