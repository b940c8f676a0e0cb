#pragma once
/// \file
/// Where the runner and the viewer look for the SCENE of their command line (README, "The
/// runner"): a path first, then, for a bare name such as `default`, the folders of
/// S2SIM_SCENE_PATH and the install's scene folder.

#include <filesystem>
#include <string>
#include <vector>

namespace s2sim::apps {

/// The folders a bare scene name is looked up in, in order: every folder of the environment
/// variable S2SIM_SCENE_PATH (':'-separated), then `<prefix>/share/s2sim/scenes`, where
/// `<prefix>` is the folder above the running executable's (so an unpacked or moved install
/// finds its own scenes); an executable of the build tree looks in the source tree's `scenes/`
/// instead, an installed one never does.
std::vector<std::filesystem::path> scene_search_path();

/// `scene` as given when it exists (a scene folder, its scene.xml or a robot file, relative to
/// the working directory); else, when it is a bare name (no '/'), the first folder of
/// scene_search_path() that holds it. Throws s2sim::Error (scene) listing every place it
/// looked and the scenes the install's folder holds.
std::filesystem::path find_scene(const std::string& scene);

}  // namespace s2sim::apps
