// The state layout (kernel/src/common/state_layout.hpp, docs/scheduling.md "Snapshots"): every
// registered segment is restored exactly and is needed. Per segment, a scene that exercises it
// is saved at t1 and run to t2 recording every signal; restoring the snapshot and replaying to
// t2 repeats the record bit for bit, and restoring it with that one segment zeroed (a variable
// segment: dropped) or taken from another time changes the replay.
#include <s2sim/kernel/simulation.hpp>

#include "common/state_layout.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using Snapshot = Simulation::Snapshot;

const fs::path kSource = S2SIM_SOURCE_DIR;

/// A scene and how it is driven.
struct Case {
  const char* name;
  fs::path scene;
  std::vector<std::pair<const char*, double>> inputs;
  double t0, t1, t2;                     // another time, the snapshot's, the replay's end
  void (*drive)(Simulation&) = nullptr;  // what is done to it after the load
};

/// Things added while running: a box dropped on the ball, which is then grown, one on the
/// floor, deleted, and one on the scene's obstacle.
void add_and_delete_things(Simulation& sim) {
  ThingSpec box;
  box.size_m = {0.1, 0.1, 0.1};
  box.pose.position = {0.02, 0, 0.4};
  sim.add_thing(box, "crate");
  box.pose.position = {1, 0, 0.05};
  const int floor_crate = sim.add_thing(box, "floor crate");
  box.pose.position = {3, 0, 0.6};
  sim.add_thing(box, "crate on the platform");  // the scene's obstacle holds it
  sim.delete_thing(floor_crate);
  // The ball grown under the first box.
  sim.resize_body(sim.things()[0].body, {0.08, 0.08, 0.08});
  sim.set_body_surface(sim.things()[0].body, 0.3, -1);
}

/// A jointed body's and a thing's mass set while running: the arm grows heavier, its centre of
/// mass moved out.
void change_masses(Simulation& sim) {
  const auto& bodies = sim.scene().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].id == "arm") {
      Simulation::MassProperties m = sim.body_mass(static_cast<int>(b + 1));
      m.mass_kg *= 2;
      m.com_m.x += 0.02;
      sim.set_body_mass(static_cast<int>(b + 1), m);
    }
}

const std::vector<Case>& cases() {
  static const std::vector<Case> c = {
      // Driving: wheels on the floor (contact memory and points), motors (components' state),
      // the speed loop's control period (published signals held between updates).
      {"nxt",
       kSource / "scenes/nxt",
       {{"robots/nxt/axes/right/ref_voltage", 6.0}, {"robots/nxt/axes/left/ref_voltage", -6.0}},
       0.2,
       0.3,
       0.45},
      // Things falling on each other: loose bodies and contact memory.
      {"pile", kSource / "scenes/pile", {}, 0.2, 0.3, 0.45},
      // Things added and deleted while running.
      {"runtime",
       kSource / "tests/kernel/sim/fixtures/runtime_things",
       {},
       0.1,
       0.2,
       0.45,
       &add_and_delete_things},
      // Kinematic loops.
      {"default", kSource / "scenes/default", {}, 0.2, 0.3, 0.45},
      // Joint reactions read by jointforce sensors, one of them noisy (random streams).
      {"jointforce",
       kSource / "tests/plugins/sensors/fixtures/jointforce",
       {{"robots/rig/axes/spin/ref_torque", 0.5}},
       0.05,
       0.1,
       0.2,
       &change_masses},
  };
  return c;
}

/// Which case shows that a segment is needed. Every segment a scene registers must be here.
const std::map<std::string, const char*>& exercised_by() {
  static const std::map<std::string, const char*> m = {
      {"multibody/time", "nxt"},
      {"multibody/q", "nxt"},
      {"multibody/u", "nxt"},
      {"multibody/columns", "nxt"},
      {"multibody/reactions", "jointforce"},
      {"loose/position", "pile"},
      {"loose/velocity", "pile"},
      {"contact/memory", "pile"},
      {"contact/points", "nxt"},
      {"components/state", "nxt"},
      {"inputs", "nxt"},
      {"published", "nxt"},
      {"axis_force_applied", "nxt"},
      {"random", "jointforce"},
      {"things", "runtime"},
      {"things/ids", "runtime"},
      {"obstacles", "runtime"},
      {"shapes", "runtime"},
      {"masses", "jointforce"},
  };
  return m;
}

// multibody/z holds Simbody's auxiliary state variables: none of the kernel's forces has any,
// so the segment is empty in every scene (checked below) and nothing can show it is needed.

std::unique_ptr<Simulation> load(const Case& c) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  auto sim = Simulation::load(c.scene, o);
  for (const auto& [name, value] : c.inputs)
    sim->set_input(name, value);
  if (c.drive) c.drive(*sim);
  return sim;
}

/// Every signal and what Simulation::things() says (present, ID), now, then after every tick
/// up to t2. A run that fails (a corrupted state may go non-finite) ends its record with a
/// marker.
std::vector<double> record(Simulation& sim, double t2) {
  std::vector<double> out;
  auto take = [&] {
    for (std::size_t i = 0; i < sim.signal_count(); ++i)
      out.push_back(sim.signal(i));
    for (const ThingView& t : sim.things()) {
      out.push_back(t.present ? 1 : 0);
      for (const char ch : t.id)
        out.push_back(ch);
    }
  };
  try {
    take();
    while (sim.time_s() < t2 - 1e-9) {
      sim.step();
      take();
    }
  } catch (const Error&) {
    out.push_back(-12345.678);
  }
  return out;
}

/// Restores `s` and records; a snapshot the kernel refuses records only a marker.
std::vector<double> replay(Simulation& sim, const Snapshot& s, double t2) {
  try {
    sim.restore(s);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::usage) << e.what();
    return {-98765.4321};
  }
  return record(sim, t2);
}

bool identical(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// `s` with segment `name` replaced by `numbers` (a variable segment may change its count).
Snapshot with_segment(const Snapshot& s, const std::string& name,
                      const std::vector<double>& numbers) {
  Snapshot out = s;
  const auto r = s.find(name);
  const auto seg = std::find_if(s.segments.begin(), s.segments.end(),
                                [&](const auto& g) { return g.name == name; });
  const bool variable = seg->size == Snapshot::Segment::variable;
  out.values.erase(out.values.begin() + static_cast<long>(r.offset),
                   out.values.begin() + static_cast<long>(r.offset + r.size));
  out.values.insert(out.values.begin() + static_cast<long>(r.offset), numbers.begin(),
                    numbers.end());
  if (variable) out.values[r.offset - 1] = static_cast<double>(numbers.size());
  return out;
}

std::vector<double> segment(const Snapshot& s, const std::string& name) {
  const auto r = s.find(name);
  return {s.values.begin() + static_cast<long>(r.offset),
          s.values.begin() + static_cast<long>(r.offset + r.size)};
}

TEST(StateLayout, EverySegmentIsRestoredExactlyAndNeeded) {
  std::set<std::string> shown;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    auto sim = load(c);
    sim->run_until(c.t0);
    const Snapshot other_time = sim->save();
    sim->run_until(c.t1);
    const Snapshot snapshot = sim->save();
    const auto original = record(*sim, c.t2);
    ASSERT_GT(original.size(), sim->signal_count());
    // Restored: the same record, bit for bit (twice: restoring does not consume the snapshot).
    for (int twice = 0; twice < 2; ++twice) {
      sim->restore(snapshot);
      EXPECT_EQ(sim->time_s(),
                snapshot.values[snapshot.find("multibody/time").offset] * sim->tick_s());
      EXPECT_TRUE(identical(record(*sim, c.t2), original));
    }
    for (const auto& seg : snapshot.segments) {
      const auto r = snapshot.find(seg.name);
      if (seg.name == "multibody/z") {
        EXPECT_EQ(r.size, 0u);
        continue;
      }
      ASSERT_TRUE(exercised_by().count(seg.name)) << "segment '" << seg.name << "' has no case";
      if (exercised_by().at(seg.name) != std::string(c.name)) continue;
      ASSERT_GT(r.size, 0u) << seg.name;
      // Zeroed, or dropped for a variable segment. The random streams' words get one bit
      // flipped instead: all-zero is xoshiro's one degenerate state (zeros forever, and
      // RandomStream::normal() waits for a non-zero draw).
      const bool variable = seg.size == Snapshot::Segment::variable;
      std::vector<double> zero(variable ? 0 : r.size, 0.0);
      if (seg.name == "random") {
        zero = segment(snapshot, seg.name);
        for (double& x : zero)
          x = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) ^ 1u);
      }
      const bool zero_changes =
          !identical(replay(*sim, with_segment(snapshot, seg.name, zero), c.t2), original);
      // From another time.
      const auto then = segment(other_time, seg.name);
      bool then_changes = false;
      if (then != segment(snapshot, seg.name)) {
        then_changes =
            !identical(replay(*sim, with_segment(snapshot, seg.name, then), c.t2), original);
      }
      EXPECT_TRUE(zero_changes || then_changes)
          << "segment '" << seg.name << "': the replay does not depend on it";
      const char* how = variable ? "dropped" : seg.name == "random" ? "bit-flipped" : "zeroed";
      std::printf("%-12s %-20s %5zu numbers: %s: %s, from another time: %s\n", c.name,
                  seg.name.c_str(), r.size, how, zero_changes ? "changes" : "same",
                  then_changes ? "changes" : "same");
      std::fflush(stdout);
      shown.insert(seg.name);
      // And the snapshot itself still restores exactly after a corrupted restore.
      sim->restore(snapshot);
      EXPECT_TRUE(identical(record(*sim, c.t2), original)) << seg.name;
    }
  }
  for (const auto& [name, scene] : exercised_by())
    EXPECT_TRUE(shown.count(name)) << "segment '" << name << "' not registered by " << scene;
}

TEST(StateLayout, ASnapshotOfAnotherSceneIsAUsageErrorNamingTheMismatch) {
  auto nxt = load(cases()[0]);
  auto pile = load(cases()[1]);
  const Snapshot snapshot = nxt->save();
  EXPECT_NE(snapshot.layout, pile->save().layout);
  try {
    pile->restore(snapshot);
    FAIL() << "restored a snapshot of another scene";
  } catch (const Error& e) {
    std::printf("%s\n", e.what());
    EXPECT_EQ(e.kind(), ErrorKind::usage);
    EXPECT_THAT(e.message(), HasSubstr("snapshot from another simulation"));
    EXPECT_THAT(e.message(), HasSubstr("numbers there"));
  }
  // Nothing changed: the pile still runs as a fresh one.
  auto fresh = load(cases()[1]);
  EXPECT_TRUE(identical(record(*pile, 0.05), record(*fresh, 0.05)));
}

TEST(StateLayout, AMalformedSnapshotIsAUsageError) {
  auto sim = load(cases()[0]);
  sim->run_until(0.1);
  Snapshot s = sim->save();
  Snapshot shorter = s;
  shorter.values.pop_back();
  EXPECT_THROW(
      {
        try {
          sim->restore(shorter);
        } catch (const Error& e) {
          EXPECT_EQ(e.kind(), ErrorKind::usage);
          throw;
        }
      },
      Error);
  Snapshot renamed = s;
  renamed.segments[1].name = "multibody/p";
  EXPECT_THROW(sim->restore(renamed), Error);
  EXPECT_THROW((void)s.find("nothing"), Error);
}

TEST(StateLayout, TheIdHashesNamesAndSizesInOrder) {
  using Entry = common::StateLayout::Entry;
  const auto id = common::StateLayout::id_of;
  EXPECT_NE(id({Entry{"a", 1}, Entry{"b", 2}}), id({Entry{"b", 2}, Entry{"a", 1}}));
  EXPECT_NE(id({Entry{"a", 1}}), id({Entry{"a", 2}}));
  EXPECT_NE(id({Entry{"a", 1}, Entry{"bc", 1}}), id({Entry{"ab", 1}, Entry{"c", 1}}));
  EXPECT_EQ(id({Entry{"a", 1}}), id({Entry{"a", 1}}));
}

}  // namespace
}  // namespace s2sim
