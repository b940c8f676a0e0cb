// Contact friction on jointed bodies, solved with the axes at the kick's end
// (docs/models/contact.md, "Friction on jointed bodies"): which bodies take points, and each
// substep's columns of the points.
//
// A wheel's rim is light across the normal (its own spin inertia over r²) while the robot it
// drives is heavy: a friction force computed at the step's start, as a spring and a damper,
// must stay soft enough for the light side, and the tyre then turns under the robot almost as
// if detached. Here each point's friction is an impulse λ found after the explicit kick, like
// the axes' Coulomb friction: with g_j = Jᵀ·d_j the generalized force of a unit force along
// tangent d_j and W = G·M⁻¹·Gᵀ (2×2 per point), the slip v = G·u − v_surface is brought to zero
// within the bound κ·μ·N, and u += M⁻¹·Gᵀ·Δλ (friction_sweeps.cpp). M⁻¹ over each tree's speeds
// is kept while the configuration that shapes it holds, turned with a free root, so that a
// point's column costs a product, not a solve. The points of a tree are swept with the tree's
// drives folded in, alternating with its axis solve (implicit_axes.cpp).
#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::model {
namespace {

/// Ranges of more speeds solve each point's columns (M^-1 would cost span² to keep).
constexpr int kMaxCachedSpeeds = 64;

/// Per body's root tree (bodies welded to Ground excluded), the ranges of its speeds and
/// coordinates and its root's index in m.roots; then each body's range (find_friction_ranges).
void number_friction_ranges(Multibody::Impl& m, const std::vector<int>& root_of,
                            const std::vector<int>& q_begin, const std::vector<int>& q_end,
                            const std::vector<char>& q_contiguous) {
  const SimTK::State& s = m.initial_state;
  const int nq = s.getNQ();
  m.friction_range.assign(m.mobod_of_body.size(), -1);
  m.friction_ranges.clear();
  std::size_t minv = 0, q_room = 0;
  for (std::size_t b = 1; b < m.mobod_of_body.size(); ++b) {
    if (m.friction_u_end[b] <= m.friction_u_begin[b]) continue;
    int id = -1;
    for (std::size_t r = 0; r < m.friction_ranges.size(); ++r)
      if (m.friction_ranges[r].u_begin == m.friction_u_begin[b] &&
          m.friction_ranges[r].u_end == m.friction_u_end[b])
        id = static_cast<int>(r);
    if (id < 0) {
      Multibody::Impl::FrictionRange range;
      range.u_begin = m.friction_u_begin[b];
      range.u_end = m.friction_u_end[b];
      const auto root = static_cast<std::size_t>(root_of[m.mobod_of_body[b]]);
      const auto& root_mob =
          m.matter.getMobilizedBody(SimTK::MobilizedBodyIndex(static_cast<int>(root)));
      // Its own tree alone: its coordinates, and its root turned with when free.
      const int span = range.u_end - range.u_begin;
      range.q_begin = q_contiguous[root] ? q_begin[root] : 0;
      range.q_end = q_contiguous[root] ? q_end[root] : nq;
      for (std::size_t k = 0; k < m.roots.size(); ++k)
        if (m.roots[k].q0 == root_mob.getFirstQIndex(s) && m.roots[k].u0 == range.u_begin &&
            q_contiguous[root])
          range.root = static_cast<int>(k);
      range.cached = span <= kMaxCachedSpeeds;
      range.minv = minv;
      range.q = q_room;
      if (range.cached) {
        minv += static_cast<std::size_t>(span) * static_cast<std::size_t>(span);
        q_room += static_cast<std::size_t>(range.q_end - range.q_begin);
      }
      id = static_cast<int>(m.friction_ranges.size());
      m.friction_ranges.push_back(range);
    }
    m.friction_range[b] = id;
  }
  m.friction_minv.assign(minv, 0.0);
  m.friction_minv_q.assign(q_room, 0.0);
  m.friction_minv_quat.assign(4 * m.friction_ranges.size(), 0.0);
  // What a cache compares: the coordinates M depends on, and the free roots' quaternions but
  // that of the range's own root, which it turns with (checked per range below).
  m.friction_q_compared.assign(static_cast<std::size_t>(nq), 0);
  for (int i = 0; i < nq; ++i)
    m.friction_q_compared[static_cast<std::size_t>(i)] =
        m.q_shapes_mass[static_cast<std::size_t>(i)];
  for (const auto& root : m.roots)
    for (int k = 0; k < 4; ++k)
      m.friction_q_compared[static_cast<std::size_t>(root.q0 + k)] = 1;
}

/// Makes range r's M^-1 current (`body` one of its bodies): kept, turned with its root, or
/// computed anew column by column.
void update_range_inverse(Multibody::Impl& m, const SimTK::State& s, int r, int body) {
  Multibody::Impl::FrictionRange& range = m.friction_ranges[static_cast<std::size_t>(r)];
  range.checked = true;
  const double* q = s.getQ().getContiguousScalarData();
  const int span = range.u_end - range.u_begin;
  double* minv = m.friction_minv.data() + range.minv;
  double* kept_q = m.friction_minv_q.data() + range.q;
  double* quat = &m.friction_minv_quat[4 * static_cast<std::size_t>(r)];
  const int own_quat = range.root >= 0 ? m.roots[static_cast<std::size_t>(range.root)].q0 : -1;
  bool same = range.valid;
  for (int i = range.q_begin; same && i < range.q_end; ++i) {
    if (!m.friction_q_compared[static_cast<std::size_t>(i)]) continue;
    if (i >= own_quat && i < own_quat + 4 && own_quat >= 0) continue;
    same = std::abs(q[i] - kept_q[i - range.q_begin]) <= 1e-7;
  }
  if (same) {
    if (own_quat < 0) return;
    bool turned = false;
    for (int k = 0; k < 4; ++k)
      turned = turned || quat[k] != q[own_quat + k];
    if (!turned) return;
    // M' = T·M·Tᵀ with T = diag(R, R, 1) on the root's (ω, v): M'^-1 = T·M^-1·Tᵀ.
    const SimTK::Rotation R =
        SimTK::Rotation(
            SimTK::Quaternion(q[own_quat], q[own_quat + 1], q[own_quat + 2], q[own_quat + 3])) *
        ~SimTK::Rotation(SimTK::Quaternion(quat[0], quat[1], quat[2], quat[3]));
    const int u0 = m.roots[static_cast<std::size_t>(range.root)].u0 - range.u_begin;
    auto turn = [&](double* x, int stride) {  // three numbers `stride` apart
      const SimTK::Vec3 v = R * SimTK::Vec3(x[0], x[stride], x[2 * stride]);
      for (int k = 0; k < 3; ++k)
        x[k * stride] = v[k];
    };
    for (int block = 0; block < 2; ++block) {
      const int first = u0 + 3 * block;
      for (int j = 0; j < span; ++j)
        turn(minv + first * span + j, span);  // T from the left: column j's block
      for (int i = 0; i < span; ++i)
        turn(minv + i * span + first, 1);  // Tᵀ from the right: row i's block
    }
    std::copy_n(q + own_quat, 4, quat);
    return;
  }
  // Anew: M^-1·e_k for each speed k of the range (M^-1 is symmetric: row k too).
  double* e = m.friction_full_g.data();
  double* column = m.friction_full_column.data();
  std::fill(e + range.u_begin, e + range.u_end, 0.0);
  for (int k = 0; k < span; ++k) {
    e[range.u_begin + k] = 1;
    m.dynamics->solve_speeds(m, s, m.mobod_of_body[static_cast<std::size_t>(body)], range.u_begin,
                             range.u_end, e, column);
    e[range.u_begin + k] = 0;
    for (int i = 0; i < span; ++i)
      minv[i * span + k] = column[range.u_begin + i];
  }
  std::copy(q + range.q_begin, q + range.q_end, kept_q);
  if (own_quat >= 0) std::copy_n(q + own_quat, 4, quat);
  range.valid = true;
}

}  // namespace

void find_friction_ranges(Multibody::Impl& m) {
  const std::size_t bodies = m.mobod_of_body.size();
  m.friction_u_begin.assign(bodies, 0);
  m.friction_u_end.assign(bodies, 0);
  m.friction_axis_tree.assign(bodies, -1);
  m.friction_group_key.assign(bodies, 0);
  m.friction_stride = 0;
  if (!m.has_mobilized_bodies || m.has_constraints) return;
  const SimTK::State& s = m.initial_state;
  const int nu = s.getNU();
  const int mobods = m.matter.getNumBodies();
  // Each mobilized body's root (its ancestor on Ground), and each root tree's speed range.
  std::vector<int> root_of(static_cast<std::size_t>(mobods), 0);
  std::vector<int> begin(static_cast<std::size_t>(mobods), nu),
      end(static_cast<std::size_t>(mobods), 0), count(static_cast<std::size_t>(mobods), 0);
  const int nq = s.getNQ();
  std::vector<int> q_begin(static_cast<std::size_t>(mobods), nq),
      q_end(static_cast<std::size_t>(mobods), 0), q_count(static_cast<std::size_t>(mobods), 0);
  for (SimTK::MobilizedBodyIndex i(1); i < mobods; ++i) {
    const auto& mob = m.matter.getMobilizedBody(i);
    const auto& parent = mob.getParentMobilizedBody();
    const int root =
        parent.isGround() ? static_cast<int>(i) : root_of[parent.getMobilizedBodyIndex()];
    root_of[i] = root;
    const auto r = static_cast<std::size_t>(root);
    const int q0 = mob.getFirstQIndex(s), n_q = mob.getNumQ(s);
    q_begin[r] = std::min(q_begin[r], q0);
    q_end[r] = std::max(q_end[r], q0 + n_q);
    q_count[r] += n_q;
    const int u0 = mob.getFirstUIndex(s), n = mob.getNumU(s);
    if (n == 0) continue;
    begin[r] = std::min(begin[r], u0);
    end[r] = std::max(end[r], u0 + n);
    count[r] += n;
  }
  // The axis tree of each root (axis_trees.cpp), when its axes are solved as their own block.
  std::vector<int> axis_tree_of_root(static_cast<std::size_t>(mobods), -1);
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    SimTK::MobilizedBodyIndex b = m.axis_impl[a].mobod;
    axis_tree_of_root[static_cast<std::size_t>(root_of[b])] = m.axis_tree[a];
  }
  const bool one_block = m.tree_u_begin.size() == 1 && m.tree_u_begin[0] == 0 &&
                         m.tree_u_end[0] == nu && !m.axes.empty();
  const int trees = static_cast<int>(m.tree_u_begin.size());
  for (std::size_t b = 1; b < bodies; ++b) {
    if (!m.mobod_of_body[b].isValid()) continue;  // loose
    const auto r = static_cast<std::size_t>(root_of[m.mobod_of_body[b]]);
    if (count[r] == 0) continue;  // welded to Ground: nothing moves
    int t = one_block ? 0 : axis_tree_of_root[r];
    int u_begin = begin[r], u_end = end[r];
    if (end[r] - begin[r] != count[r]) u_begin = 0, u_end = nu;  // interleaved: every speed
    if (t >= 0) {
      u_begin = std::min(u_begin, m.tree_u_begin[static_cast<std::size_t>(t)]);
      u_end = std::max(u_end, m.tree_u_end[static_cast<std::size_t>(t)]);
    }
    m.friction_u_begin[b] = u_begin;
    m.friction_u_end[b] = u_end;
    m.friction_axis_tree[b] = t;
    m.friction_group_key[b] = t >= 0 ? t : trees + u_begin;
    m.friction_stride = std::max(m.friction_stride, u_end - u_begin);
  }
  // A range's coordinates: its tree's, when they are contiguous and the range is the tree's.
  std::vector<char> q_contiguous(static_cast<std::size_t>(mobods), 0);
  for (std::size_t r = 1; r < static_cast<std::size_t>(mobods); ++r)
    q_contiguous[r] = q_end[r] - q_begin[r] == q_count[r] && end[r] - begin[r] == count[r];
  for (std::size_t b = 1; b < bodies; ++b) {  // ranges wider than their tree: every coordinate
    if (!m.mobod_of_body[b].isValid() || m.friction_u_end[b] <= m.friction_u_begin[b]) continue;
    const auto r = static_cast<std::size_t>(root_of[m.mobod_of_body[b]]);
    if (m.friction_u_begin[b] != begin[r] || m.friction_u_end[b] != end[r]) q_contiguous[r] = 0;
  }
  number_friction_ranges(m, root_of, q_begin, q_end, q_contiguous);
}

bool Multibody::solves_contact_friction(int body) const {
  const Impl& m = *impl_;
  const auto b = static_cast<std::size_t>(body);
  return body > 0 && b < m.friction_u_end.size() && m.friction_u_end[b] > m.friction_u_begin[b];
}

void Multibody::reserve_contact_friction(std::int32_t points) {
  Impl& m = *impl_;
  // At most 32 MB of rows: past that, a point's friction stays the contact's force law.
  const std::size_t stride = static_cast<std::size_t>(std::max(1, m.friction_stride));
  const std::size_t most = std::max<std::size_t>(64, (std::size_t{1} << 21) / stride);
  const std::size_t n = std::min(static_cast<std::size_t>(std::max(0, points)), most);
  m.friction_storage.assign(n, FrictionPoint{});
  m.friction.points = m.friction_storage.data();
  m.friction.count = 0;
  m.friction.capacity = static_cast<std::int32_t>(n);
  m.friction_g.assign(2 * n * stride, 0.0);
  m.friction_column.assign(2 * n * stride, 0.0);
  m.friction_block_size.assign(n, 0);
  m.friction_block_factored.assign(n, 0);
  m.friction_block_w.assign(64 * n, 0.0);  // kBlockRoom (friction_sweeps.cpp)
  m.friction_block_rhs.assign(6 * kMaxBlockPoints + 4 * kMaxBlockPoints * kMaxBlockPoints, 0.0);
  m.friction_effective_column.assign(2 * n * stride, 0.0);
  m.friction_effective_w.assign(4 * n, 0.0);
  const std::size_t most_axes = m.rows_axes.size();  // the largest tree's (axis_trees.cpp)
  m.friction_linear.assign(most_axes, 0);
  m.friction_built_linear.assign(most_axes, 0);
  m.friction_scale.assign(most_axes, 0.0);
  m.friction_rhs.assign(most_axes, 0.0);
  m.friction_coupling.assign(most_axes * most_axes, 0.0);
  m.friction_impulse.assign(2 * n, 0.0);
  m.friction_order.assign(n, 0);
  m.friction_group_start.assign(n + 1, 0);
  const auto nu = static_cast<std::size_t>(m.initial_state.getNU());
  m.friction_full_g.assign(2 * nu, 0.0);  // (one row per tangent)
  m.friction_full_column.assign(nu, 0.0);
  m.friction_scratch.resize(static_cast<int>(nu));
}

FrictionPoints* Multibody::contact_friction() {
  return &impl_->friction;
}

bool prepare_contact_friction(Multibody::Impl& m, const SimTK::State& s) {
  const int count = m.friction.count;
  m.friction_groups = 0;
  if (count <= 0) return false;
  const FrictionPoint* points = m.friction.points;
  const auto key = [&](int i) {
    return m.friction_group_key[static_cast<std::size_t>(points[i].body)];
  };
  // Ordered by group, stably (insertion: the points come grouped already, body by body).
  int* order = m.friction_order.data();
  for (int i = 0; i < count; ++i) {
    int j = i;
    while (j > 0 && key(order[j - 1]) > key(i)) {
      order[j] = order[j - 1];
      --j;
    }
    order[j] = i;
  }
  for (int n = 0; n < count; ++n) {
    if (n == 0 || key(order[n]) != key(order[n - 1]))
      m.friction_group_start[static_cast<std::size_t>(m.friction_groups++)] = n;
  }
  m.friction_group_start[static_cast<std::size_t>(m.friction_groups)] = count;
  // Blocks: runs of a group's points (a robot's tread points).
  for (int n = 0; n < count;) {
    int k = 1;
    while (n + k < count && k < kMaxBlockPoints && key(order[n + k]) == key(order[n]))
      ++k;
    m.friction_block_size[static_cast<std::size_t>(n)] = k;
    for (int q = 1; q < k; ++q)
      m.friction_block_size[static_cast<std::size_t>(n + q)] = 0;
    n += k;
  }

  const auto stride = static_cast<std::size_t>(m.friction_stride);
  for (auto& range : m.friction_ranges)
    range.checked = false;
  for (int i = 0; i < count; ++i) {
    const FrictionPoint& p = points[i];
    const auto b = static_cast<std::size_t>(p.body);
    const int begin = m.friction_u_begin[b], span = m.friction_u_end[b] - begin;
    double* g[2];
    double* c[2];
    const int r = m.friction_range[b];
    Multibody::Impl::FrictionRange& range = m.friction_ranges[static_cast<std::size_t>(r)];
    if (range.cached && !range.checked) update_range_inverse(m, s, r, p.body);
    const double* minv = m.friction_minv.data() + range.minv;
    // Both tangents' g over every speed, then the range's.
    const std::size_t nu = m.friction_full_column.size();
    double* full_g[2] = {m.friction_full_g.data(), m.friction_full_g.data() + nu};
    const SimTK::Vec3 directions[2] = {
        SimTK::Vec3(p.direction[0].x, p.direction[0].y, p.direction[0].z),
        SimTK::Vec3(p.direction[1].x, p.direction[1].y, p.direction[1].z)};
    m.dynamics->point_forces(m, s, m.mobod_of_body[b],
                             SimTK::Vec3(p.point_m.x, p.point_m.y, p.point_m.z), directions, begin,
                             begin + span, full_g);
    for (int j = 0; j < 2; ++j) {
      const std::size_t row =
          (2 * static_cast<std::size_t>(i) + static_cast<std::size_t>(j)) * stride;
      g[j] = m.friction_g.data() + row;
      c[j] = m.friction_column.data() + row;
      std::copy_n(full_g[j] + begin, span, g[j]);
      if (!range.cached) {
        m.dynamics->solve_speeds(m, s, m.mobod_of_body[b], begin, begin + span, full_g[j],
                                 m.friction_full_column.data());
        std::copy_n(m.friction_full_column.data() + begin, span, c[j]);
      }
    }
    if (range.cached) {  // M^-1·g from the kept inverse, over g's non-zero speeds
      for (int j = 0; j < 2; ++j) {
        std::fill(c[j], c[j] + span, 0.0);
        for (int k = 0; k < span; ++k) {
          const double gk = g[j][k];
          if (gk == 0.0) continue;
          const double* row_k = minv + static_cast<std::size_t>(k) * static_cast<std::size_t>(span);
          for (int e = 0; e < span; ++e)
            c[j][e] += gk * row_k[e];
        }
      }
    }
    m.friction_impulse[2 * static_cast<std::size_t>(i)] = 0;
    m.friction_impulse[2 * static_cast<std::size_t>(i) + 1] = 0;
  }
  return true;
}

void copy_raw_friction(Multibody::Impl& m, int group) {
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  for (int n = m.friction_group_start[static_cast<std::size_t>(group)];
       n < m.friction_group_start[static_cast<std::size_t>(group) + 1]; ++n) {
    const auto i = static_cast<std::size_t>(m.friction_order[static_cast<std::size_t>(n)]);
    std::copy_n(m.friction_column.data() + 2 * i * stride, 2 * stride,
                m.friction_effective_column.data() + 2 * i * stride);
  }
}

void uncoupled_friction(Multibody::Impl& m, int group) {
  copy_raw_friction(m, group);
  // Each point's W here only: a group coupled to its drives has its own.
  const auto stride = static_cast<std::size_t>(m.friction_stride);
  for (int n = m.friction_group_start[static_cast<std::size_t>(group)];
       n < m.friction_group_start[static_cast<std::size_t>(group) + 1]; ++n) {
    const auto i = static_cast<std::size_t>(m.friction_order[static_cast<std::size_t>(n)]);
    const auto b = static_cast<std::size_t>(m.friction.points[i].body);
    const double* g = m.friction_g.data() + 2 * i * stride;
    const double* c = m.friction_column.data() + 2 * i * stride;
    friction_pair_w(g, g + stride, c, c + stride, m.friction_u_end[b] - m.friction_u_begin[b],
                    &m.friction_effective_w[4 * i]);
  }
  build_friction_blocks(m, group);
}

int friction_group_tree(const Multibody::Impl& m, int group) {
  const int first = m.friction_order[static_cast<std::size_t>(
      m.friction_group_start[static_cast<std::size_t>(group)])];
  return m.friction_axis_tree[static_cast<std::size_t>(m.friction.points[first].body)];
}

void finish_contact_friction(Multibody::Impl& m, double kick_s) {
  for (int i = 0; i < m.friction.count; ++i) {
    FrictionPoint& p = m.friction.points[i];
    const double* lambda = &m.friction_impulse[2 * static_cast<std::size_t>(i)];
    p.force_N =
        kick_s > 0 ? (lambda[0] * p.direction[0] + lambda[1] * p.direction[1]) / kick_s : Vec3{};
  }
}

}  // namespace s2sim::model
