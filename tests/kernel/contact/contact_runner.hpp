#pragma once
// The multibody test runner (tests/kernel/model/model_runner.hpp) with the contact layer on its
// scene: shared by the contact tests.
#include "contact/contact_world.hpp"
#include "model/multibody.hpp"
#include "model_runner.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace s2sim::test {

struct ContactRunner : Runner {
  explicit ContactRunner(const scene::Scene& s, double dt = 1e-3, int substeps = 1)
      : Runner(s, dt, substeps), table(s), contacts(table, s, mb.apparent_mass_kg()) {
    // As the simulation does (sim/load.cpp).
    contacts.set_mobility(mb.contact_mobility());
    mb.reserve_contact_friction(contacts.point_capacity());
    std::vector<char> solved(static_cast<std::size_t>(mb.body_count()), 0);
    for (std::size_t b = 1; b < solved.size(); ++b)
      solved[b] = mb.solves_contact_friction(static_cast<int>(b));
    contacts.set_solved_friction(solved);
    contact = &contacts;
    mb.use_contact_wrenches();
  }
  /// The deepest point among the last substep's contacts.
  double deepest_m() const {
    double d = 0;
    for (std::int32_t i = 0; i < *contacts.contact_count(); ++i)
      d = std::max(d, contacts.contacts()[i].depth_m);
    return d;
  }
  collision::ShapeTable table;
  contact::ContactWorld contacts;
};

}  // namespace s2sim::test
