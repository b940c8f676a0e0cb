#pragma once
/// \file
/// Versions of the S2Sim SDK. A plugin records the versions it was built against in its
/// descriptor; the kernel refuses a plugin whose ABI version or SDK major version differs from
/// its own, or whose SDK minor version is newer than the kernel's.

#define S2SIM_SDK_VERSION_MAJOR 0
#define S2SIM_SDK_VERSION_MINOR 17
#define S2SIM_SDK_VERSION_PATCH 0

/// Bumped whenever a type that crosses the plugin boundary changes layout: the descriptor, the
/// kind entry, a virtual table (`Component`, `ConfigureContext`, `Params`), a type passed
/// through them (`SensorSpec`...), or `s2sim::detail::WorldView`.
#define S2SIM_PLUGIN_ABI_VERSION 12

namespace s2sim {
/// The SDK version as a "major.minor.patch" string.
inline constexpr const char* kSdkVersionString = "0.17.0";
}  // namespace s2sim
