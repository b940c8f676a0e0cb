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

/// The plan of the components by part, made at load (Simulation::Impl::plan_component_parts).
struct ComponentParts {
  struct alignas(64) Part {  // a cache line apart: each is written by its own thread
    LocalView local;         ///< its axis_drives: the part's own slots
    std::array<std::vector<int>, 4> stage_order;  ///< its components, in the serial order
    std::vector<int> bodies, axes;                ///< what it steps (kernel bodies, scene axes)
  };
  /// Empty: the components run on the calling thread, stage by stage (serial_reason says why).
  std::vector<Part> parts;
  std::string serial_reason;
};

}  // namespace s2sim::sim
