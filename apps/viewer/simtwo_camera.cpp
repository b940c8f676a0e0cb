#include "simtwo_camera.hpp"

#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <map>

namespace s2sim::viewer {
namespace {

/// The `key=value` lines of an INI file (sections ignored: the keys used here are unique).
std::map<std::string, std::string> read_ini(const std::filesystem::path& file) {
  std::map<std::string, std::string> values;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto eq = line.find('=');
    if (eq != std::string::npos && line[0] != '[') values[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return values;
}

/// Three numbers named prefix + X/Y/Z + suffix, from the first file that has all three.
std::optional<Vec3f> read_vector(const std::filesystem::path& folder,
                                 std::initializer_list<const char*> files,
                                 const std::string& prefix, const std::string& suffix,
                                 std::string& source) {
  for (const char* name : files) {
    const auto values = read_ini(folder / name);
    float xyz[3];
    int found = 0;
    for (int i = 0; i < 3; ++i) {
      const auto it = values.find(prefix + "XYZ"[i] + suffix);
      if (it == values.end()) break;
      char* end = nullptr;
      xyz[i] = std::strtof(it->second.c_str(), &end);
      if (end == it->second.c_str()) break;
      ++found;
    }
    if (found == 3) {
      source += source.empty() ? name : std::string(", ") + name;
      return Vec3f{xyz[0], xyz[1], xyz[2]};
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<SavedCamera> read_simtwo_camera(const std::filesystem::path& folder) {
  SavedCamera camera;
  const auto eye = read_vector(folder, {"config_Viewer.ini", "SimTwo.ini"},
                               "GLDummyCamPos_Position", "", camera.source);
  const auto target = read_vector(folder, {"config_Params.ini", "SimTwo.ini"}, "EditSetCamLook",
                                  "_Text", camera.source);
  if (!eye || !target || dot(*eye - *target, *eye - *target) < 1e-6f) return std::nullopt;
  camera.eye_m = *eye;
  camera.target_m = *target;
  return camera;
}

}  // namespace s2sim::viewer
