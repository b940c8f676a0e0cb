#pragma once
/// \file
/// What the tests of the parallel step share (parallel_islands_test.cpp, run_ahead_test.cpp):
/// scenes loaded at a thread count, and their signals and contacts compared bit for bit.

#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>
#include "common/temp_dir.hpp"

namespace s2sim::parallel_runs {

inline const std::filesystem::path kRobots16 =
    std::filesystem::path(S2SIM_SOURCE_DIR) / "bench/peers/scenes/robots_16";
/// Robots of two parts driven into each other, into a wall and into loose things.
inline const std::filesystem::path kRobotsMeeting =
    std::filesystem::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/robots_meeting";

inline bool two_threads_available() {
  return std::thread::hardware_concurrency() >= 2;
}

inline std::unique_ptr<Simulation> load_on(const std::filesystem::path& scene, int threads) {
  SimulationOptions o;
  o.threads = threads;
  return Simulation::load(scene, o);
}

/// Calls f(index, name) for every input whose name ends in /ref_voltage.
template <class F>
void each_voltage(Simulation& sim, F&& f) {
  for (std::size_t i = 0; i < sim.input_count(); ++i) {
    const std::string& name = sim.input_info(i).name;
    if (name.size() > 12 && name.compare(name.size() - 12, 12, "/ref_voltage") == 0) f(i, name);
  }
}

/// `scene` with each robot's wheels at their own voltages: the robots turn on circles of
/// their own.
inline std::unique_ptr<Simulation> load_driven(const std::filesystem::path& scene, int threads) {
  auto sim = load_on(scene, threads);
  std::size_t k = 0;
  each_voltage(*sim, [&](std::size_t i, const std::string&) {
    sim->set_input(i, 2.0 + 0.37 * static_cast<double>(k++ % 23));
  });
  return sim;
}

/// kRobotsMeeting with every robot driven straight ahead.
inline std::unique_ptr<Simulation> load_meeting(int threads) {
  auto sim = load_on(kRobotsMeeting, threads);
  each_voltage(*sim, [&](std::size_t i, const std::string& name) {
    sim->set_input(i, name.find("/left/") != std::string::npos ? -6.0 : 6.0);
  });
  return sim;
}

/// A scene of four copies of `robot_file` in a row along x, `spacing_m` apart, named
/// <prefix>0 … <prefix>3 (the first two are dealt to part 0, the others to part 1), then
/// `extra` (e.g. `<plugin>` elements), written into the test's folder `folder`: the folder.
inline std::filesystem::path row_scene(const std::string& folder,
                                       const std::filesystem::path& robot_file,
                                       const std::string& prefix, double spacing_m,
                                       const std::string& extra = "") {
  const auto row = s2sim::test::process_temp_dir() / folder;
  std::filesystem::create_directories(row);
  std::ofstream f(row / "scene.xml");
  f << "<scene>\n";
  for (int r = 0; r < 4; ++r)
    f << "<robot><ID name='" << prefix << r << "'/><pos x='" << spacing_m * r
      << "' y='0' z='0'/><body file='" << robot_file.string() << "'/></robot>\n";
  f << extra << "</scene>\n";
  return row;
}

/// Every signal's bits, in order.
inline std::vector<double> signals(const Simulation& sim) {
  std::vector<double> out(sim.signal_count());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = sim.signal(i);
  return out;
}

inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// Whether contact `c` of both runs is the same to the bit (bodies, point, normal, force,
/// depth).
inline bool same_contact(const Simulation& a_run, const Simulation& b_run, std::size_t c) {
  const ContactInfo &a = a_run.contact(c), &b = b_run.contact(c);
  return a.body_a.index == b.body_a.index && a.body_b.index == b.body_b.index &&
         std::memcmp(&a.point_m, &b.point_m, sizeof(Vec3)) == 0 &&
         std::memcmp(&a.normal, &b.normal, sizeof(Vec3)) == 0 &&
         std::memcmp(&a.force_N, &b.force_N, sizeof(Vec3)) == 0 &&
         std::memcmp(&a.depth_m, &b.depth_m, sizeof(double)) == 0;
}

/// Steps `serial` `ticks` times one by one and `parallel` once by step(ticks) (so that its
/// parts may run ahead), then whether every signal and every contact is the same to the bit,
/// a failure naming the first that is not; calls `each(contact)` for every contact.
template <class F>
bool step_and_compare(Simulation& serial, Simulation& parallel, int ticks, F&& each) {
  for (int tick = 0; tick < ticks; ++tick)
    serial.step();
  parallel.step(ticks);
  if (!same_bits(signals(serial), signals(parallel))) {
    ADD_FAILURE() << "signals differ after tick " << serial.tick();
    return false;
  }
  if (serial.contact_count() != parallel.contact_count()) {
    ADD_FAILURE() << "contact counts differ after tick " << serial.tick();
    return false;
  }
  for (std::size_t c = 0; c < serial.contact_count(); ++c) {
    if (!same_contact(serial, parallel, c)) {
      ADD_FAILURE() << "contact " << c << " differs after tick " << serial.tick();
      return false;
    }
    each(serial.contact(c));
  }
  return true;
}

}  // namespace s2sim::parallel_runs
