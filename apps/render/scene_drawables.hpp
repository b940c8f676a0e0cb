#pragma once
/// \file
/// The scene turned into things to draw: each solid and shell primitive (or its mesh), each
/// obstacle, track polygon, sensor beam and joint marker, attached to the body that moves it.
/// Built once per loaded scene; every frame only the body poses change.

#include "renderer.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::render {

struct Drawable {
  /// `canvas`: the square on a box's +Z face showing its canvas image (SimTwo's `<canvas>`).
  enum class Kind { solid, shell, obstacle, track, beam, joint, canvas };
  Kind kind = Kind::solid;
  int body = 0;                        ///< simulation body index (0 = world, scene body i = i + 1)
  Mat4 local;                          ///< mesh to body frame (scale included)
  Vec3f box_min{-0.5f, -0.5f, -0.5f};  ///< mesh-space bounds, for picking
  Vec3f box_max{0.5f, 0.5f, 0.5f};
  DrawItem item;                                 ///< model is rewritten every frame
  float scene_color[4] = {0.5f, 0.5f, 0.5f, 1};  ///< the scene's; a script may repaint a solid
  int index = 0;   ///< a geom's index in its body (0: the solid), an obstacle's, a sensor's
  int thing = -1;  ///< its body's index in Simulation::things(), -1 for other bodies
  /// A primitive's frame in its body (`local` without the scale) and kind, for a resize while
  /// running (Simulation::resized); meshes keep theirs.
  bool primitive = false;
  scene::ShapeType shape = scene::ShapeType::box;
  Mat4 frame, loaded_local;
  bool hidden = false;  ///< a deleted thing, or a spare body no thing holds
  /// Drawn as a mesh a component chose while running (Annotations::body_meshes); the scene's
  /// picture kept to go back to.
  bool run_time_mesh = false;
  DrawItem scene_item;
  Vec3f scene_box_min, scene_box_max;
  Mat4 scene_local;
  /// A canvas: the drawable of its box (earlier in the list) and its texture in
  /// SceneDrawables::canvases_; `frame` places the square in the box's unit frame.
  int owner = -1;
  int canvas = -1;
};

class SceneDrawables {
 public:
  /// Builds the drawables of `scene`, uploading meshes and textures into `renderer`. Missing
  /// or unreadable mesh and texture files are reported in `warnings` and drawn as the
  /// primitive (or untextured).
  void build(const scene::Scene& scene, Renderer& renderer, std::vector<std::string>& warnings);

  /// Draws solids as the meshes components chose while running (StepContext::set_body_mesh)
  /// and back as the scene's when they are forgotten; reads a file once. Only when the
  /// annotations changed. Files it cannot read are reported in `warnings`.
  void take_meshes(const Simulation& sim, Renderer& renderer, std::vector<std::string>& warnings);

  /// Uploads each canvas image (a `<canvas>` box's: `<body path>/canvas`, `obstacles/<i>/canvas`)
  /// whose frame counter changed since its last upload, into its texture. Looks the images up
  /// at its first call; no allocation after it.
  void take_canvases(const Simulation& sim, Renderer& renderer);

  /// Updates every item's model matrix from the simulation's body poses, each solid's colour
  /// from the run-time colours (`Annotations::body_colors`), and the liquid surfaces
  /// (`Annotations::liquid_surfaces`), as wide as the floor (`floor_half_size_m`). No
  /// allocation.
  void update(const Simulation& sim, float floor_half_size_m) {
    const std::vector<Pose>& poses = sim.body_poses();
    update(sim, poses.data(), static_cast<int>(poses.size()), floor_half_size_m);
  }
  /// The same with the bodies at `body_poses` (by body index, `body_count` of them: a camera
  /// drawn during a step); the rest still comes from `sim`. A body beyond `body_count` is
  /// hidden.
  void update(const Simulation& sim, const Pose* body_poses, int body_count,
              float floor_half_size_m);

  /// Items to hand to the renderer (sensor beams and joint markers filtered by the flags),
  /// those of `selected_body` highlighted.
  const std::vector<DrawItem>& items(bool beams, bool joints, int selected_body);

  /// The body hit first by the ray (world frame), or -1; `distance_m` is set on a hit.
  int pick(const Vec3f& origin, const Vec3f& direction, float& distance_m) const;

  /// World-frame bounds of the solids, shells and obstacles at this frame's poses (after
  /// update), of `robot`'s bodies only when `robot` >= 0 (track polygons, beams and joint
  /// markers left out). False when there is nothing to bound.
  bool bounds(const scene::Scene& scene, int robot, Vec3f& lo, Vec3f& hi) const;

  const std::vector<Drawable>& drawables() const { return drawables_; }

 private:
  /// `d`'s mesh and bounds for primitive `s`, its scale appended to `d.local`.
  void take_primitive(Drawable& d, const scene::Shape& s) const;
  /// A thing added while running takes its primitive, size and colour from its spec.
  void take_thing_shape(Drawable& d, const ThingView& thing);

  struct LoadedMesh {
    int mesh = -1;  ///< from Renderer::upload; -1: the file could not be read
    Vec3f lo, hi;   ///< bounds of its vertices
  };
  /// `file`'s mesh at `scale`, read and uploaded once per scene.
  LoadedMesh load_mesh(Renderer& renderer, const std::filesystem::path& file, double scale,
                       std::vector<std::string>& warnings);
  /// `d` drawn as `loaded` (its `shadow_file`, when named, for the shadow and small on screen).
  void take_mesh(Drawable& d, const LoadedMesh& loaded, bool casts_shadow, Renderer& renderer,
                 const std::filesystem::path& shadow_file, double scale,
                 std::vector<std::string>& warnings);
  std::map<std::pair<std::filesystem::path, double>, LoadedMesh> mesh_cache_;
  std::uint64_t meshes_version_ = 0;

  /// The fire effect's flames (Annotations::fire), placed by update(); empty while out.
  void place_fire(const Simulation& sim, const Pose* body_poses, int body_count);
  static constexpr int kFlames = 3;
  DrawItem flames_[kFlames];
  bool burning_ = false;
  /// The liquid surfaces, one translucent slab per height (components at the same height
  /// share it), placed by update().
  void place_liquids(const Simulation& sim, float half_size_m);
  static constexpr int kMaxLiquids = 8;
  DrawItem liquids_[kMaxLiquids];
  float liquid_z_m_[kMaxLiquids] = {};
  int liquid_count_ = 0;

  /// A canvas image and its texture.
  struct CanvasTexture {
    int body = 0;       ///< the box's body (0: an obstacle)
    int obstacle = -1;  ///< the obstacle's index, -1 for a body's
    bool looked_up = false;
    const Image* image = nullptr;  ///< null when the simulation has no such image
    unsigned texture = 0;
    std::uint64_t uploaded_frame = 0;
    bool uploaded = false;
  };
  std::vector<CanvasTexture> canvases_;
  int canvas_square_ = -1;

  std::vector<Drawable> drawables_;
  std::vector<DrawItem> items_;  ///< reused every frame
  int box_ = -1, cylinder_ = -1, sphere_ = -1, cylinder_coarse_ = -1, sphere_coarse_ = -1;
};

}  // namespace s2sim::render
