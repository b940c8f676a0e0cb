#include "floor_look.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace s2sim::render {
namespace {

namespace fs = std::filesystem;

/// A check box's state ("1"/"0") from config_Params.ini (SimTwo's newer layout), else
/// SimTwo.ini (older projects keep every form there).
std::optional<bool> read_check_box(const fs::path& folder, const std::string& key,
                                   std::vector<std::string>& sources) {
  for (const char* name : {"config_Params.ini", "SimTwo.ini"}) {
    std::ifstream in(folder / name);
    for (std::string line; std::getline(in, line);) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.rfind(key + "=", 0) != 0) continue;
      const std::string value = line.substr(key.size() + 1);
      if (value != "0" && value != "1") continue;  // not a check box state: ignored
      if (std::find(sources.begin(), sources.end(), name) == sources.end())
        sources.emplace_back(name);
      return value == "1";
    }
  }
  return std::nullopt;
}

bool parse_float(const std::string& text, float& value) {
  char* end = nullptr;
  value = std::strtof(text.c_str(), &end);
  return end != text.c_str() && *end == '\0';
}

}  // namespace

FloorLook read_floor_look(const fs::path& folder, std::vector<std::string>& warnings) {
  FloorLook look;
  look.grid = read_check_box(folder, "CBGrid_Checked", look.sources);
  look.shadows = read_check_box(folder, "CBShadows_Checked", look.sources);
  look.sky = read_check_box(folder, "CBSkyDome_Checked", look.sources);

  // params.cfg: tab-separated rows "Name<TAB>value<TAB>value...".
  const fs::path params = folder / "params.cfg";
  std::ifstream in(params);
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string f; std::getline(row, f, '\t');)
      if (!f.empty()) fields.push_back(f);
    if (fields.empty()) continue;
    const std::string where = params.string() + ":" + std::to_string(line_number);
    if (fields[0] == "Floor.Diffuse.Color") {
      std::array<float, 3> rgb{};
      bool ok = fields.size() >= 4;
      for (int i = 0; ok && i < 3; ++i)
        ok = parse_float(fields[i + 1], rgb[i]) && rgb[i] >= 0 && rgb[i] <= 1;
      if (!ok) {
        warnings.push_back(where + ": Floor.Diffuse.Color: '" + line +
                           "' is not three numbers from 0 to 1; the default floor colour is used");
        continue;
      }
      look.color = rgb;
      if (look.sources.empty() || look.sources.back() != "params.cfg")
        look.sources.emplace_back("params.cfg");
    } else if (fields[0] == "Floor.Texture") {
      // S2Sim's row: the image (relative to the folder) and the side of one copy in metres.
      float tile_m = 1;
      if (fields.size() < 2 ||
          (fields.size() >= 3 && (!parse_float(fields[2], tile_m) || !(tile_m > 0)))) {
        warnings.push_back(where + ": Floor.Texture: '" + line +
                           "' is not a file name and a tile size in metres > 0; ignored");
        continue;
      }
      look.texture_file = folder / fields[1];
      look.texture_tile_m = tile_m;
      look.texture_source = where + ": Floor.Texture";
      if (look.sources.empty() || look.sources.back() != "params.cfg")
        look.sources.emplace_back("params.cfg");
    }
  }
  // A SimTwo project's own ground image, when params.cfg names none.
  if (look.texture_file.empty())
    for (const char* name : {"ground.jpg", "ground.png", "ground.bmp"})
      if (std::error_code ec; fs::is_regular_file(folder / name, ec)) {
        look.texture_file = folder / name;
        look.texture_source = "the project's ground image";
        look.sources.emplace_back(name);
        break;
      }
  return look;
}

}  // namespace s2sim::render
