// A jointed body's mobility at its centre of mass for the contact layer (multibody.hpp,
// Multibody::contact_mobility): unit wrenches through Simbody's M⁻¹ at load.
#include "model/multibody_impl.hpp"

#include <cmath>

namespace s2sim::model {

LoadResponse::LoadResponse(const Multibody::Impl& m)
    : m_(m), load_(m.matter.getNumBodies()), accel_(m.matter.getNumBodies()) {}

void LoadResponse::clear() {
  load_.setToZero();
}

void LoadResponse::add(const SimTK::State& s, std::size_t b, const SimTK::Vec3& torque,
                       const SimTK::Vec3& force) {
  load_[mobod(b).getMobilizedBodyIndex()] =
      SimTK::SpatialVec(torque + SimTK::cross(com_G(s, b), force), force);  // about the origin
}

void LoadResponse::solve(const SimTK::State& s) {
  m_.matter.multiplyBySystemJacobianTranspose(s, load_, f_);
  m_.matter.multiplyByMInv(s, f_, udot_);
  m_.matter.multiplyBySystemJacobian(s, udot_, accel_);
}

std::pair<SimTK::Vec3, SimTK::Vec3> LoadResponse::at_com(const SimTK::State& s,
                                                         std::size_t b) const {
  const SimTK::SpatialVec& A = accel_[mobod(b).getMobilizedBodyIndex()];
  return {A[0], A[1] + SimTK::cross(A[0], com_G(s, b))};
}

std::vector<Multibody::Mobility> Multibody::contact_mobility() const {
  const Impl& m = *impl_;
  const SimTK::State& s = m.initial_state;
  m.system.realize(s, SimTK::Stage::Position);
  std::vector<Mobility> out(m.mobod_of_body.size());
  std::vector<int> kernel_of_mobod(static_cast<std::size_t>(m.matter.getNumBodies()), 0);
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b)
    if (m.mobod_of_body[b].isValid()) kernel_of_mobod[m.mobod_of_body[b]] = static_cast<int>(b);
  LoadResponse response(m);
  auto base = [&](std::size_t b) -> const SimTK::MobilizedBody& {
    return response.mobod(b).getBaseMobilizedBody();
  };
  // Only trees whose base is free: a base jointed to the world answers some pushes not at
  // all (an infinite effective mass); those keep the apparent mass and their own inertia.
  const auto rounds = response.rounds([&](std::size_t b) {
    return kernel_of_mobod[base(b).getMobilizedBodyIndex()] > 0 && base(b).getNumU(s) == 6;
  });
  for (const auto& bodies : rounds) {
    for (int column = 0; column < 6; ++column) {
      // A unit torque (columns 0-2) or a unit force at the COM (3-5), along a root axis.
      SimTK::Vec3 unit(0);
      unit[column % 3] = 1;
      const SimTK::Vec3 zero(0);
      response.clear();
      for (std::size_t b : bodies) {
        const SimTK::Vec3 along = base(b).getBodyRotation(s) * unit;
        response.add(s, b, column < 3 ? along : zero, column < 3 ? zero : along);
      }
      response.solve(s);
      for (std::size_t b : bodies) {
        const SimTK::Rotation& R = base(b).getBodyRotation(s);  // root axes -> ground
        const auto [alpha, a_com] = response.at_com(s, b);
        const SimTK::Vec3 angular = ~R * alpha;
        const SimTK::Vec3 linear = ~R * a_com;
        Mobility& out_b = out[b];
        for (int row = 0; row < 3; ++row) {
          out_b.phi[row][column] = angular[row];
          out_b.phi[row + 3][column] = linear[row];
        }
      }
    }
    for (std::size_t b : bodies) {
      Mobility& out_b = out[b];
      out_b.root = kernel_of_mobod[base(b).getMobilizedBodyIndex()];
      bool finite = true;
      for (const auto& row : out_b.phi)
        for (double x : row)
          finite = finite && std::isfinite(x);
      if (!finite) out_b = Mobility{};
    }
  }
  return out;
}

}  // namespace s2sim::model
