// libs2sim.so is the static kernel linked whole (kernel/CMakeLists.txt); this file only gives
// the shared library a translation unit of its own, and its version for `strings`/debuggers.
#include <s2sim/version.hpp>

namespace s2sim {
/// The version libs2sim.so was built with ("major.minor.patch"): S2Sim's single version.
extern const char* const kLibraryVersion;
const char* const kLibraryVersion = kSdkVersionString;
}  // namespace s2sim
