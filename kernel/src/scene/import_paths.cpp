/// \file
/// The model search path and URI resolution of imported robots: `package://` (ROS),
/// `model://` (Gazebo), `file://` and plain paths (docs/models/import.md, "Files and URIs").

#include "scene/import_model.hpp"

#include <cstdlib>
#include <system_error>

namespace s2sim::scene::detail {
namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

void append_env(std::vector<fs::path>& out, const char* variable) {
  const char* value = std::getenv(variable);
  if (!value) return;
  std::string s(value);
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find(':', start);
    const std::string part = s.substr(start, end == std::string::npos ? end : end - start);
    if (!part.empty()) out.emplace_back(part);
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

}  // namespace

std::vector<fs::path> model_search_path(const std::vector<fs::path>& extra) {
  std::vector<fs::path> out = extra;
  for (const char* variable : {"S2SIM_MODEL_PATH", "ROS_PACKAGE_PATH", "GZ_SIM_RESOURCE_PATH",
                               "IGN_GAZEBO_RESOURCE_PATH", "GAZEBO_MODEL_PATH"})
    append_env(out, variable);
  return out;
}

fs::path resolve_model_uri(const std::string& uri, const fs::path& base_dir,
                           const std::vector<fs::path>& search_path, const Location& where) {
  for (const char* scheme : {"package://", "model://"}) {
    const std::string prefix(scheme);
    if (uri.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = uri.substr(prefix.size());
    const std::size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? std::string() : rest.substr(slash + 1);
    if (name.empty() || inside.empty())
      throw Error(ErrorKind::scene, where,
                  "URI '" + uri + "' has no " + (name.empty() ? "package" : "file") + " part");
    // The search path: a folder holding the package (or model), or the package itself; then
    // the folders above the file that names it, so that a description unpacked anywhere finds
    // its own meshes.
    std::vector<fs::path> searched;
    auto try_root = [&](const fs::path& root) -> std::optional<fs::path> {
      searched.push_back(root);
      if (is_file(root / name / inside)) return (root / name / inside).lexically_normal();
      if (root.filename() == name && is_file(root / inside))
        return (root / inside).lexically_normal();
      return std::nullopt;
    };
    for (const fs::path& root : search_path)
      if (auto found = try_root(root)) return *found;
    for (fs::path up = base_dir; !up.empty(); up = up.parent_path()) {
      if (auto found = try_root(up)) return *found;
      if (up == up.parent_path()) break;
    }
    std::string list;
    for (const fs::path& s : searched)
      list += "\n  " + s.generic_string();
    throw Error(ErrorKind::scene, where,
                "cannot resolve '" + uri + "': no " +
                    (prefix == "package://" ? "package '" : "model '") + name + "' holding '" +
                    inside +
                    "' in the model path (--model-path, S2SIM_MODEL_PATH, ROS_PACKAGE_PATH, "
                    "GZ_SIM_RESOURCE_PATH) or above the file; searched:" +
                    list);
  }
  std::string path = uri;
  if (path.compare(0, 7, "file://") == 0) path = path.substr(7);
  if (path.find("://") != std::string::npos)
    throw Error(
        ErrorKind::scene, where,
        "URI '" + uri + "': unknown scheme (expected package://, model://, file:// or a path)");
  fs::path p(path);
  if (!p.is_absolute()) p = base_dir / p;
  p = p.lexically_normal();
  if (!is_file(p))
    throw Error(ErrorKind::scene, where,
                "file '" + uri + "' not found (looked for " + p.generic_string() + ")");
  return p;
}

}  // namespace s2sim::scene::detail
