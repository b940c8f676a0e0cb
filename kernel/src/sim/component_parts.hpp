#pragma once
/// \file
/// Components stepped in the island parts (docs/scheduling.md, "Components in parts"): with
/// several threads, when every component of the scene declared itself local
/// (ConfigureContext::declare_local) and each group of components that touch one another
/// touches the bodies and axes of one part only, each part's thread runs its group's updates
/// at the tick's start, before its physics, at the same time as the others
/// (component_parts.cpp). The components' order within a part is the serial run's; parts share
/// nothing they write, so the results are the serial run's, bit for bit.

#include <s2sim/component.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace s2sim::sim {

/// What a component resolved through its ConfigureContext: for a local one, everything its
/// update() may touch besides its own signals, state and random stream.
struct Footprint {
  std::vector<std::int32_t> bodies;     ///< kernel bodies (the world left out)
  std::vector<std::int32_t> axes;       ///< scene-wide axes
  std::vector<std::int32_t> joints;     ///< scene joints
  std::vector<std::int32_t> inputs;     ///< declared, joined or looked up
  std::vector<std::int32_t> published;  ///< published-signal slots it reads
  std::vector<std::int32_t> readers;    ///< signal entries of its SignalReaders
};

/// The view a local component's update() gets: the world's buffers with rays, requests and
/// annotations refused by name (Simulation::Impl::refuse_*), and in a part the part's own
/// drive slots. `view.kernel`, `placer` and `annotator` point back here.
struct LocalView {
  detail::WorldView view;
  const void* sim = nullptr;    ///< the Simulation::Impl
  std::int32_t component = -1;  ///< the one whose update() runs (for the refusal)
};

/// A group of components stepped together at the tick's start: their stages in the serial
/// order, then the reference torques on their axes and the check of their loads
/// (Simulation::Impl::run_component_group, one function for every group).
struct alignas(64) ComponentGroup {  // a cache line apart: each is written by its own thread
  /// The physics part whose thread runs the group before its substeps (MultibodyIslands'
  /// TickHooks); kWholeScene: every component, on the calling thread before the physics.
  int part = kWholeScene;
  static constexpr int kWholeScene = -1;
  /// The view of its local components (a part's: its own drive slots).
  LocalView local;
  std::array<std::vector<int>, 4> stage_order;  ///< its components, in the serial order
  std::vector<int> bodies, axes;  ///< the loads it clears (the whole scene: the world's too)
};

/// The plan of the components, made at load (Simulation::Impl::plan_component_parts): one
/// group per physics part when every component is local and each group of components that
/// touch one another touches one part, else the whole scene's group.
struct ComponentParts {
  ComponentGroup whole;
  /// Empty: the components run as `whole` (serial_reason says why).
  std::vector<ComponentGroup> parts;
  std::string serial_reason;
};

}  // namespace s2sim::sim
