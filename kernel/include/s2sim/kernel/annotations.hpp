#pragma once
/// \file
/// What components publish for the people watching a simulation (SDK 0.9:
/// `StepContext::log_line`, `set_hud_text`, `add_trail_point`, `add_xy_point`, and the colours,
/// meshes and fire of later versions): log lines, HUD texts, trails, XY series and how bodies look.
/// The viewer draws them (s2sim-run does not read them). They are not part of the simulation's
/// state: a reset forgets them and a snapshot does not hold them. Every list is bounded, so a
/// component publishing every tick cannot exhaust memory.

#include <s2sim/math.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace s2sim {

struct Annotations {
  static constexpr std::size_t kMaxLines = 1000;  ///< log lines kept
  /// Bytes kept of one log line or HUD text: longer ones are cut, the cut said at their end,
  /// so that the kept lines stay under about 4 MB however long each one is.
  static constexpr std::size_t kMaxTextBytes = 4096;
  static constexpr std::size_t kMaxPoints = 10000;        ///< points kept per trail or series
  static constexpr std::size_t kMaxTrailsOrSeries = 256;  ///< per simulation; more are ignored

  struct Line {
    std::uint64_t sequence = 0;  ///< 0, 1, 2... since the load or the last reset
    double time_s = 0;           ///< simulated time of the tick that published it
    std::string source;          ///< the component's signal prefix, e.g. `controllers/script`
    std::string text;
  };
  struct Hud {
    std::string source;
    std::string text;  ///< lines separated by '\n'
  };
  struct Trail {
    std::string source;
    int id = 0;
    std::deque<Vec3> points_m;  ///< oldest first, world frame
  };
  struct XySeries {
    std::string source;
    int id = 0;
    std::deque<std::pair<double, double>> points;  ///< oldest first
  };

  std::deque<Line> lines;  ///< the latest kMaxLines, oldest first
  std::uint64_t next_sequence = 0;
  std::vector<Hud> huds;  ///< one per component that set a non-empty text, in order of first use
  std::vector<Trail> trails;
  std::vector<XySeries> series;
  /// Bodies painted at run time (StepContext::set_body_color), one entry per body.
  struct BodyColor {
    int body = 0;
    double rgb[3] = {0, 0, 0};  ///< 0..1
  };
  std::vector<BodyColor> body_colors;
  /// Geoms painted at run time (StepContext::set_shape_color): a body's geom (1: its first
  /// shell), or on body 0 the scene's obstacle `geom`; one entry per geom.
  struct ShapeColor {
    int body = 0;
    int geom = 0;
    double rgb[3] = {0, 0, 0};
  };
  std::vector<ShapeColor> shape_colors;
  const ShapeColor* shape_color(int body, int geom) const;
  /// Scene sensors painted at run time (StepContext::set_sensor_color), by index in
  /// scene::Scene::sensors.
  struct SensorColor {
    int sensor = 0;
    double rgb[3] = {0, 0, 0};
  };
  std::vector<SensorColor> sensor_colors;
  /// The fire effect (StepContext::set_fire): flames at `position_m` in body `body`'s frame.
  struct Fire {
    bool burning = false;
    int body = 0;
    Vec3 position_m;
    Vec3 scale{1, 1, 1};
  };
  Fire fire;
  /// Solids drawn as a mesh file (StepContext::set_body_mesh), one entry per body.
  struct BodyMesh {
    int body = 0;
    std::filesystem::path file;         ///< absolute (a relative one is the scene folder's)
    std::filesystem::path shadow_file;  ///< empty: the mesh itself casts the shadow
    double scale = 1;
    bool casts_shadow = true;
  };
  std::vector<BodyMesh> body_meshes;
  const BodyMesh* body_mesh(int body) const;
  /// Liquid surfaces (StepContext::show_liquid_surface), one per component that showed one.
  struct LiquidSurface {
    std::string source;
    double z_m = 0;
    double rgba[4] = {0, 0, 0, 0};  ///< 0..1
  };
  std::vector<LiquidSurface> liquid_surfaces;
  /// Forgets what was painted on or drawn for `body` (a spare body taken by a new thing).
  void forget_body(int body);
  const SensorColor* sensor_color(int sensor) const;
  /// The run-time colour of `body`, or null when it keeps the scene's.
  const BodyColor* body_color(int body) const;
  /// Incremented whenever anything changes (a viewer redraws or copies only then).
  std::uint64_t version = 0;

  /// Lines with a sequence number >= `sequence`, oldest first.
  std::vector<Line> lines_from(std::uint64_t sequence) const;
  /// All HUD texts joined, one component after the other.
  std::string hud_text() const;
  void clear();
};

}  // namespace s2sim
