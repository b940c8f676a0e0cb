// The choice of the equations of motion (dynamics.hpp), made here and nowhere else.
#include "model/dynamics.hpp"

namespace s2sim::model {

void select_dynamics(Multibody::Impl& m) {
  // The tree computes joint reactions without loops only: with loops Simbody's count the
  // constraint forces.
  const bool tree_possible = m.tree && !(m.reactions_wanted && m.has_constraints);
  const Dynamics* chosen = &simbody_dynamics();
  if (tree_possible && m.choice == DynamicsChoice::tree_where_possible) chosen = &tree_dynamics();
  if (tree_possible && m.choice == DynamicsChoice::checked) chosen = &checked_dynamics();
  m.dynamics = chosen;
  m.reference_udot.resize(chosen == &checked_dynamics() ? m.udot.size() : 0);
  m.bodies_fresh = false;
}

}  // namespace s2sim::model
