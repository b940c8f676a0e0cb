#pragma once
/// \file
/// A spray-painting scene written into a folder of its own: a square plate (a thing resting
/// on the floor, its top face a painting target meshed as a grid of equal right triangles,
/// plate.obj) under a world-fixed `spraygun` pointing straight down at its centre; optionally
/// an obstacle sheet between them over x > 0, and a script.

#include <filesystem>
#include <fstream>
#include <string>

namespace s2sim::test {

struct SprayScene {
  double side_m = 0.4;      ///< the plate's edge
  int cells = 100;          ///< grid cells per edge: 2·cells² triangles
  double plate_x_m = 0;     ///< where the plate's centre stands
  double height_m = 0.3;    ///< of the nozzle above the plate's top face (z = 0.01)
  double rate_m3_s = 1e-6;  ///< paint_rate
  double max_angle_rad = 0.3;
  bool on = true;          ///< paint_default_on
  bool occlusion = false;  ///< paint_occlusion
  bool blocker = false;    ///< a sheet halfway up over x in [0.01, 0.31]
  std::string gun_extra;   ///< more children of the <spraygun> element
  std::string script;      ///< a control.pas to write (and name in <s2sim><script>)
};

/// The plate's top face, z = 0.005 in its body frame (the box is 0.01 thick): cells x cells
/// squares, each cut into two triangles wound anticlockwise seen from +Z.
inline void write_plate_obj(const std::filesystem::path& file, double side_m, int cells) {
  std::ofstream out(file);
  const double h = side_m / cells;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i)
      out << "v " << -side_m / 2 + i * h << ' ' << -side_m / 2 + j * h << " 0.005\n";
  auto at = [&](int i, int j) { return j * (cells + 1) + i + 1; };  // OBJ counts from 1
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      out << "f " << at(i, j) << ' ' << at(i + 1, j) << ' ' << at(i + 1, j + 1) << '\n';
      out << "f " << at(i, j) << ' ' << at(i + 1, j + 1) << ' ' << at(i, j + 1) << '\n';
    }
}

/// Writes the scene into `dir` (created); returns `dir`.
inline std::filesystem::path write_spray_scene(const std::filesystem::path& dir,
                                               const SprayScene& s) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  write_plate_obj(dir / "plate.obj", s.side_m, s.cells);
  std::ofstream(dir / "things.xml")
      << "<?xml version='1.0' ?>\n<things>\n  <cuboid>\n    <ID value='plate'/>\n"
      << "    <mass value='1'/>\n    <size x='" << s.side_m << "' y='" << s.side_m
      << "' z='0.01'/>\n    <pos x='" << s.plate_x_m << "' y='0' z='0.005'/>\n"
      << "    <mesh file='plate.obj'/>\n    <painting_target/>\n  </cuboid>\n</things>\n";
  std::ofstream(dir / "sensors.xml")
      << "<?xml version='1.0' ?>\n<sensors>\n  <spraygun>\n    <ID value='gun'/>\n"
      << "    <pos x='0' y='0' z='" << 0.01 + s.height_m << "'/>\n    <rot_deg y='90'/>\n"
      << "    <paint_rate value='" << s.rate_m3_s << "'/>\n"
      << "    <paint_max_angle value='" << s.max_angle_rad << "'/>\n"
      << "    <paint_default_on value='" << (s.on ? 1 : 0) << "'/>\n"
      << "    <paint_occlusion value='" << (s.occlusion ? 1 : 0) << "'/>\n"
      << s.gun_extra << "  </spraygun>\n</sensors>\n";
  std::ofstream(dir / "obstacles.xml")
      << "<?xml version='1.0' ?>\n<obstacles>\n"
      << (s.blocker ? "  <cuboid>\n    <ID value='sheet'/>\n    <size x='0.3' y='0.6' "
                      "z='0.002'/>\n    <pos x='0.16' y='0' z='" +
                          std::to_string(0.01 + s.height_m / 2) + "'/>\n  </cuboid>\n"
                    : std::string())
      << "</obstacles>\n";
  std::ofstream scene(dir / "scene.xml");
  scene << "<?xml version='1.0' ?>\n<scene>\n  <things file='things.xml'/>\n"
        << "  <obstacles file='obstacles.xml'/>\n  <sensors file='sensors.xml'/>\n";
  if (!s.script.empty()) {
    std::ofstream(dir / "control.pas") << s.script;
    scene << "  <s2sim>\n    <script file='control.pas'/>\n  </s2sim>\n";
  }
  scene << "</scene>\n";
  return dir;
}

}  // namespace s2sim::test
