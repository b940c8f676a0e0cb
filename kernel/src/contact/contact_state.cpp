// The contact layer's state in a snapshot (contact_world.hpp, declare_state): the points'
// memory and the last substep's contact list, as variable-length segments.
#include "contact/contact_world.hpp"

#include "common/state_layout.hpp"

#include <algorithm>

namespace s2sim::contact {

void ContactWorld::declare_state(common::StateLayout& layout) {
  constexpr std::size_t kPer = 13;
  layout.add_variable(
      "contact/memory", kPer,
      [this] {
        std::size_t count = 0;
        for (const Lane& lane : lanes_)
          count += lane.memory.size();
        return kPer * count;
      },
      [this](double* out) {
        // In key order whatever the lanes: the lanes' runs merged.
        merge_lanes([&](std::size_t l) { return lanes_[l].memory.size(); },
                    [&](std::size_t l, std::size_t i, std::size_t k, std::size_t j) {
                      return lanes_[l].memory[i].key < lanes_[k].memory[j].key;
                    },
                    [&](std::size_t l, std::size_t i) {
                      const Memory& m = lanes_[l].memory[i];
                      const PointState& p = m.state;
                      const double v[kPer] = {std::bit_cast<double>(m.key),
                                              p.bristle_m.x,
                                              p.bristle_m.y,
                                              p.bristle_m.z,
                                              p.approach_speed_m_s,
                                              p.local_point_m.x,
                                              p.local_point_m.y,
                                              p.local_point_m.z,
                                              p.impact_pending ? 1.0 : 0.0,
                                              p.held_force_N,
                                              p.rest_depth_m,
                                              p.rest_rate_m_s,
                                              p.last_depth_m};
                      out = std::copy(v, v + kPer, out);
                    });
      },
      [this](const double* in, std::size_t count) {
        for (Lane& lane : lanes_)
          lane.memory.clear();
        for (std::size_t k = 0; k < count; k += kPer, in += kPer) {
          Memory m;
          m.key = std::bit_cast<std::uint64_t>(in[0]);
          m.state.bristle_m = {in[1], in[2], in[3]};
          m.state.approach_speed_m_s = in[4];
          m.state.local_point_m = {in[5], in[6], in[7]};
          m.state.impact_pending = in[8] != 0;
          m.state.held_force_N = in[9];
          m.state.rest_depth_m = in[10];
          m.state.rest_rate_m_s = in[11];
          m.state.last_depth_m = in[12];
          // A key names its first shape: its lane keeps it (a key from another scene: lane 0).
          const std::uint64_t shape = m.key >> 40;
          (shape < lane_of_shape_.size() ? lane_of(static_cast<std::int32_t>(shape)) : lanes_[0])
              .memory.push_back(m);
        }
      });
  // The last substep's contacts: what touch sensors and the contact signals read next.
  constexpr std::size_t kInfo = 12;
  layout.add_variable(
      "contact/points", kInfo,
      [this] {
        merge_parts();
        return kInfo * info_.size();
      },
      [this](double* out) {
        merge_parts();
        for (const ContactInfo& c : info_) {
          const double v[kInfo] = {static_cast<double>(c.body_a.index),
                                   static_cast<double>(c.body_b.index),
                                   c.point_m.x,
                                   c.point_m.y,
                                   c.point_m.z,
                                   c.normal.x,
                                   c.normal.y,
                                   c.normal.z,
                                   c.force_N.x,
                                   c.force_N.y,
                                   c.force_N.z,
                                   c.depth_m};
          out = std::copy(v, v + kInfo, out);
        }
      },
      [this](const double* in, std::size_t count) {
        in_lanes_ = lanes_hold_last_ = false;  // the restored list is the whole one
        info_.clear();
        for (std::size_t k = 0; k < count; k += kInfo, in += kInfo) {
          ContactInfo c;
          c.body_a = BodyHandle{static_cast<std::int32_t>(in[0])};
          c.body_b = BodyHandle{static_cast<std::int32_t>(in[1])};
          c.point_m = {in[2], in[3], in[4]};
          c.normal = {in[5], in[6], in[7]};
          c.force_N = {in[8], in[9], in[10]};
          c.depth_m = in[11];
          info_.push_back(c);
        }
        info_count_ = static_cast<std::int32_t>(info_.size());
      });
}

}  // namespace s2sim::contact
