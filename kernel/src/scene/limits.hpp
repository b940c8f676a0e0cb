#pragma once
/// \file
/// Resource limits of a scene, checked at load with located errors (docs/reliability.md): a
/// count or a step beyond them would exhaust memory or time rather than simulate anything.

#include <s2sim/image.hpp>

#include <cstdint>

namespace s2sim::scene::limits {

/// Substeps per physics step (the runner's --substeps has the same bound).
inline constexpr std::int64_t kMaxSubsteps = 1000;
/// The physics step: from 1 µs to 1 s (--physics-step has the same bounds).
inline constexpr double kMinPhysicsStep_s = 1e-6;
inline constexpr double kMaxPhysicsStep_s = 1.0;
/// A solid's or shell's size or radius, m (10 km): beyond it the narrow phase loses its
/// precision and FCL/libccd may not terminate.
inline constexpr double kMaxLength_m = 1e4;
/// Nesting of XML elements (SimTwo's scenes nest a dozen deep; the parsers recurse).
inline constexpr std::int64_t kMaxXmlDepth = 256;
/// Elements of one XML file (a 3 000-body pile is about 25 000): checked by a scan before the
/// tree is built, which takes some 500 bytes per element.
inline constexpr std::int64_t kMaxXmlElements = 500000;
/// Copies one track element makes with `<repeat times>`.
inline constexpr std::int64_t kMaxTrackRepeats = 10000;
/// Segments of one track arc ((stop − start) / step).
inline constexpr std::int64_t kMaxArcSegments = 100000;

/// Spare bodies for things added while running: at most this many (`<s2sim><runtime_things>`),
/// and this many when a scene's script adds things and the scene does not say.
inline constexpr std::int64_t kMaxRuntimeThings = 4096;
inline constexpr int kDefaultRuntimeThings = 32;

/// Triangles of one painting target's mesh (SimTwo's GetPaintTargetTriangles gives at most
/// this many): a spray gun publishes one thickness per triangle.
inline constexpr std::int64_t kMaxPaintTriangles = 200000;

// Rays of one sensor beam: s2sim::kMaxBeamRays (s2sim/sensor.hpp, shared with the plugins).
// A camera's or canvas's width or height in pixels, and a camera's frame decimation:
// s2sim::kMaxImageSide_px (s2sim/image.hpp, shared with the plugins).

}  // namespace s2sim::scene::limits
