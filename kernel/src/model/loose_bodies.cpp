#include "model/loose_bodies.hpp"

#include "common/state_layout.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {
namespace {

Quat normalized(const Quat& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}

}  // namespace

void LooseBodies::add(int kernel_index, const scene::Body& body) {
  Model m;
  m.kernel_index = kernel_index;
  m.mass_kg = body.mass_kg;
  m.com_body_m = body.com_m;
  m.inertia_body = body.inertia_kg_m2;
  m.inverse_inertia_body = inverse(body.inertia_kg_m2);
  m.gravity = body.gravity;
  m.com0_m = body.pose * body.com_m;
  m.q0 = to_quat(body.pose.rotation);
  model_.push_back(m);
  state_.push_back({m.com0_m, {}, {}, m.q0});
  rotation_.push_back(to_matrix(m.q0));
}

bool LooseBodies::set_mass_properties(int kernel_index, double mass_kg, const Vec3& com_m,
                                      const Mat3& inertia, bool gravity, bool fixed) {
  for (std::size_t i = 0; i < model_.size(); ++i) {
    Model& m = model_[i];
    if (m.kernel_index != kernel_index) continue;
    State& s = state_[i];
    s.com_m += rotation_[i] * (com_m - m.com_body_m);  // the origin stays put
    m.mass_kg = mass_kg;
    m.com_body_m = com_m;
    m.inertia_body = inertia;
    m.inverse_inertia_body = inverse(inertia);
    m.gravity = gravity;
    m.fixed = fixed;
    if (fixed) s.com_velocity_m_s = s.angular_velocity_rad_s = Vec3{};
    return true;
  }
  return false;
}

void LooseBodies::refresh_rotations() {
  for (std::size_t i = 0; i < state_.size(); ++i)
    rotation_[i] = to_matrix(state_[i].q);
}

void LooseBodies::reset() {
  for (std::size_t i = 0; i < model_.size(); ++i)
    state_[i] = {model_[i].com0_m, {}, {}, model_[i].q0};
  refresh_rotations();
}

void LooseBodies::kick(const Wrench* wrenches, const Wrench* extra, double kick_s) {
  for (std::size_t i = 0; i < model_.size(); ++i) {
    const Model& m = model_[i];
    if (m.fixed) continue;
    State& s = state_[i];
    Wrench w = wrenches[m.kernel_index];
    if (extra) {
      w.force_N += extra[m.kernel_index].force_N;
      w.torque_Nm += extra[m.kernel_index].torque_Nm;
    }
    const Mat3& r = rotation_[i];
    // Wrenches are about the body origin; Newton–Euler wants them about the COM.
    const Vec3 com_from_origin = r * m.com_body_m;
    const Vec3 torque_com = w.torque_Nm - cross(com_from_origin, w.force_N);
    Vec3 accel = w.force_N / m.mass_kg;
    if (m.gravity) accel.z -= kGravity_m_s2;
    // I·dω/dt = τ − ω × (I·ω), in body axes.
    const Mat3 rt = r.transposed();
    const Vec3 omega_b = rt * s.angular_velocity_rad_s;
    const Vec3 tau_b = rt * torque_com;
    const Vec3 alpha_b =
        m.inverse_inertia_body * (tau_b - cross(omega_b, m.inertia_body * omega_b));
    s.com_velocity_m_s += accel * kick_s;
    s.angular_velocity_rad_s += (r * alpha_b) * kick_s;
  }
}

void LooseBodies::drift(double step_s) {
  for (std::size_t i = 0; i < state_.size(); ++i) {
    State& s = state_[i];
    s.com_m += s.com_velocity_m_s * step_s;
    const Vec3& w = s.angular_velocity_rad_s;
    const Quat& q = s.q;
    // dq/dt = ½ (0, ω) ⊗ q, ω in the world frame.
    const Quat dq{
        -0.5 * (w.x * q.x + w.y * q.y + w.z * q.z), 0.5 * (w.x * q.w + w.y * q.z - w.z * q.y),
        0.5 * (-w.x * q.z + w.y * q.w + w.z * q.x), 0.5 * (w.x * q.y - w.y * q.x + w.z * q.w)};
    s.q = normalized(
        {q.w + step_s * dq.w, q.x + step_s * dq.x, q.y + step_s * dq.y, q.z + step_s * dq.z});
    rotation_[i] = to_matrix(s.q);
  }
}

void LooseBodies::read(Pose* poses, Twist* twists) const {
  for (std::size_t i = 0; i < model_.size(); ++i) {
    const Model& m = model_[i];
    const State& s = state_[i];
    const Mat3& r = rotation_[i];
    const Vec3 com_from_origin = r * m.com_body_m;
    poses[m.kernel_index] = {s.com_m - com_from_origin, r};
    twists[m.kernel_index] = {
        s.angular_velocity_rad_s,
        s.com_velocity_m_s - cross(s.angular_velocity_rad_s, com_from_origin)};
  }
}

double LooseBodies::kinetic_energy_J() const {
  double e = 0;
  for (std::size_t i = 0; i < model_.size(); ++i) {
    const State& s = state_[i];
    const Vec3 omega_b = to_matrix(s.q).transposed() * s.angular_velocity_rad_s;
    e += 0.5 * model_[i].mass_kg * dot(s.com_velocity_m_s, s.com_velocity_m_s) +
         0.5 * dot(omega_b, model_[i].inertia_body * omega_b);
  }
  return e;
}

double LooseBodies::potential_energy_J() const {
  double e = 0;
  for (std::size_t i = 0; i < model_.size(); ++i)
    if (model_[i].gravity) e += model_[i].mass_kg * kGravity_m_s2 * state_[i].com_m.z;
  return e;
}

double LooseBodies::checksum() const {
  double sum = 0;
  for (const State& s : state_)
    sum += s.com_m.x + s.com_m.y + s.com_m.z + s.com_velocity_m_s.x + s.com_velocity_m_s.y +
           s.com_velocity_m_s.z + s.angular_velocity_rad_s.x + s.angular_velocity_rad_s.y +
           s.angular_velocity_rad_s.z + s.q.w + s.q.x + s.q.y + s.q.z;
  return sum;
}

void LooseBodies::declare_state(common::StateLayout& layout, const std::string& prefix) {
  layout.add(
      prefix + "/position", 7 * state_.size(),
      [this](double* out) {
        for (const State& s : state_) {
          const double v[7] = {s.com_m.x, s.com_m.y, s.com_m.z, s.q.w, s.q.x, s.q.y, s.q.z};
          out = std::copy(v, v + 7, out);
        }
      },
      [this](const double* in, std::size_t) {
        for (State& s : state_) {
          s.com_m = {in[0], in[1], in[2]};
          s.q = {in[3], in[4], in[5], in[6]};
          in += 7;
        }
        refresh_rotations();
      });
  layout.add(
      prefix + "/velocity", 6 * state_.size(),
      [this](double* out) {
        for (const State& s : state_) {
          const Vec3 &v = s.com_velocity_m_s, &w = s.angular_velocity_rad_s;
          const double x[6] = {v.x, v.y, v.z, w.x, w.y, w.z};
          out = std::copy(x, x + 6, out);
        }
      },
      [this](const double* in, std::size_t) {
        for (State& s : state_) {
          s.com_velocity_m_s = {in[0], in[1], in[2]};
          s.angular_velocity_rad_s = {in[3], in[4], in[5]};
          in += 6;
        }
      });
}

bool LooseBodies::set_velocity(int kernel_index, const Twist& twist) {
  for (std::size_t i = 0; i < model_.size(); ++i) {
    if (model_[i].kernel_index != kernel_index) continue;
    State& b = state_[i];
    const Vec3 com_from_origin = rotation_[i] * model_[i].com_body_m;
    b.com_velocity_m_s = twist.linear_m_s + cross(twist.angular_rad_s, com_from_origin);
    b.angular_velocity_rad_s = twist.angular_rad_s;
    return true;
  }
  return false;
}

bool LooseBodies::move(int kernel_index, const Pose& pose) {
  for (std::size_t i = 0; i < model_.size(); ++i) {
    if (model_[i].kernel_index != kernel_index) continue;
    state_[i].com_m = pose * model_[i].com_body_m;
    state_[i].q = normalized(to_quat(pose.rotation));
    rotation_[i] = to_matrix(state_[i].q);
    return true;
  }
  return false;
}

bool LooseBodies::place(int kernel_index, const Pose& pose) {
  for (std::size_t i = 0; i < model_.size(); ++i) {
    if (model_[i].kernel_index != kernel_index) continue;
    state_[i] = {pose * model_[i].com_body_m, {}, {}, normalized(to_quat(pose.rotation))};
    rotation_[i] = to_matrix(state_[i].q);
    return true;
  }
  return false;
}

}  // namespace s2sim::model
