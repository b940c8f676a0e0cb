// A jointed body's mass properties changed while running (SimTwo's SetSolidMass; the kernel's
// Simulation::set_body_mass). Simbody holds a body's mass properties in its topology: the
// system is realized anew and the state carried over, coordinate for coordinate. The tree
// dynamics, the weights, the joint stops and the cached M^-1 columns follow.
#include "model/multibody_impl.hpp"

namespace s2sim::model {
namespace {

/// `old` moved onto the system's new topology: its coordinates, speeds and auxiliary states.
SimTK::State carried_over(Multibody::Impl& m, const SimTK::State& old) {
  SimTK::State state = default_state(m);
  state.updQ() = old.getQ();
  state.updU() = old.getU();
  state.updZ() = old.getZ();
  m.system.realize(state, SimTK::Stage::Velocity);
  return state;
}

bool has_children(const Multibody::Impl& m, SimTK::MobilizedBodyIndex i) {
  for (SimTK::MobilizedBodyIndex k(1); k < m.matter.getNumBodies(); ++k)
    if (m.matter.getMobilizedBody(k).getParentMobilizedBody().getMobilizedBodyIndex() == i)
      return true;
  return false;
}

}  // namespace

bool Multibody::set_jointed_mass(int body, double mass_kg, const Vec3& com_m, const Mat3& inertia) {
  Impl& m = *impl_;
  if (body <= 0 || body >= static_cast<int>(m.mobod_of_body.size())) return false;
  const SimTK::MobilizedBodyIndex mobod = m.mobod_of_body[static_cast<std::size_t>(body)];
  if (!mobod.isValid()) return false;
  const Mat3& I = inertia;
  SimTK::Inertia inertia_com(I.m[0][0], I.m[1][1], I.m[2][2], I.m[0][1], I.m[0][2], I.m[1][2]);
  inertia_com += m.joint_disk_inertia[static_cast<std::size_t>(body)];
  const SimTK::Vec3 com = to_simtk(com_m);
  const SimTK::MassProperties mp(mass_kg, com, inertia_com.shiftFromMassCenter(-com, mass_kg));
  m.matter.updMobilizedBody(mobod).setDefaultMassProperties(mp);
  m.system.realizeTopology();
  m.initial_state = carried_over(m, m.initial_state);
  m.current = carried_over(m, m.current);

  for (Impl::Weight& w : m.weights)
    if (w.mobod == mobod) {
      w.mass_kg = mass_kg;
      w.com_m = com;
    }
  if (m.tree) {
    double mass = 0;
    Vec3 com_B;
    Mat3 central;
    central_mass_of(mp, mass, com_B, central);
    m.tree->set_mass(mobod, mass, com_B, central);
  }
  // Whether turning a leaf wheel shapes the mass matrix may have changed with its mass centre.
  const SimTK::MobilizedBody& mob = m.matter.getMobilizedBody(mobod);
  if (m.matter.getNumConstraints() == 0 && SimTK::MobilizedBody::Pin::isInstanceOf(mob) &&
      !has_children(m, mobod))
    m.q_shapes_mass[static_cast<std::size_t>(mob.getFirstQIndex(m.initial_state))] =
        turning_keeps_mass(m, mobod, m.initial_state) ? 0 : 1;
  // The stops as they would have been tuned at load for this mass.
  if (!m.stops.empty()) tune_stops(m, m.initial_state, kStopRinging * m.substeps / m.tick_s);
  clear_columns(m);
  m.bodies_fresh = false;
  return true;
}

}  // namespace s2sim::model
