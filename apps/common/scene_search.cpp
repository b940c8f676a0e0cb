#include "scene_search.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <cstdlib>
#include <system_error>

namespace s2sim::apps {
namespace fs = std::filesystem;

namespace {

fs::path running_executable() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe;
}

// Whether the running executable is one of this build tree's (bin/ of the build).
bool in_build_tree(const fs::path& exe) {
#ifdef S2SIM_BUILD_BIN_DIR
  std::error_code ec;
  return !exe.empty() && fs::equivalent(exe.parent_path(), fs::path(S2SIM_BUILD_BIN_DIR), ec);
#else
  (void)exe;
  return false;
#endif
}

}  // namespace

std::vector<fs::path> scene_search_path() {
  std::vector<fs::path> folders;
  if (const char* env = std::getenv("S2SIM_SCENE_PATH")) {
    const std::string value = env;
    std::size_t start = 0;
    while (start <= value.size()) {
      std::size_t end = value.find(':', start);
      if (end == std::string::npos) end = value.size();
      if (end > start) folders.emplace_back(value.substr(start, end - start));
      start = end + 1;
    }
  }
  const fs::path exe = running_executable();
  if (in_build_tree(exe)) {
#ifdef S2SIM_SOURCE_SCENE_DIR
    folders.emplace_back(S2SIM_SOURCE_SCENE_DIR);
#endif
  } else if (!exe.empty()) {
    folders.push_back((exe.parent_path() / ".." / "share" / "s2sim" / "scenes").lexically_normal());
  }
  return folders;
}

fs::path find_scene(const std::string& scene) {
  std::error_code ec;
  const fs::path given(scene);
  if (fs::exists(given, ec)) return given;
  std::string looked = "\n  " + fs::absolute(given, ec).lexically_normal().string();
  const bool bare_name =
      !scene.empty() && scene.find('/') == std::string::npos && scene != "." && scene != "..";
  const std::vector<fs::path> folders = scene_search_path();
  if (bare_name) {
    for (const fs::path& folder : folders) {
      const fs::path candidate = folder / scene;
      if (fs::exists(candidate, ec)) return candidate;
      looked += "\n  " + candidate.string();
    }
  }
  std::string message = "scene '" + scene + "' not found; looked at, in order:" + looked;
  if (!bare_name) message += "\n(a name holding a '/' is only a path)";
  // The scenes there, so that a misspelt name shows the right one.
  for (const fs::path& folder : folders) {
    std::vector<std::string> names;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_directory(ec)) names.push_back(it->path().filename().string());
    if (names.empty()) continue;
    std::sort(names.begin(), names.end());
    message += "\nscenes in " + folder.string() + ":";
    for (const auto& n : names)
      message += " " + n;
  }
  throw Error(ErrorKind::scene, message);
}

}  // namespace s2sim::apps
