#pragma once
/// \file
/// A SimTwo project's saved camera: the eye is the viewer's `GLDummyCamPos_Position{X,Y,Z}`
/// (config_Viewer.ini, else SimTwo.ini's [Viewer]), the point looked at the configuration
/// form's `EditSetCamLook{X,Y,Z}_Text` (config_Params.ini, else SimTwo.ini). Both in metres,
/// Z up, as S2Sim's world.

#include "render_names.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace s2sim::viewer {

struct SavedCamera {
  Vec3f eye_m, target_m;
  std::string source;  ///< the file(s) it came from, for the log
};

/// The project's saved camera, or nothing when the folder has no such settings (or they are
/// not numbers, or the eye sits on the target).
std::optional<SavedCamera> read_simtwo_camera(const std::filesystem::path& folder);

}  // namespace s2sim::viewer
