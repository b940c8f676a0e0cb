#include "camera_images.hpp"

#include "../sensor_frames.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

namespace s2sim::viewer {
namespace {

/// The lidar's points in the world frame, coloured by their distance from the sensor.
void rebuild_cloud(const Simulation& sim, const Image& image, CameraImage& entry) {
  entry.cloud_m.clear();
  entry.cloud_colours.clear();
  if (entry.sensor < 0) return;
  const Pose pose = sensor_world_pose(sim, entry.sensor);
  std::vector<float>& ranges = entry.cloud_ranges_m;  // reused: no allocation once grown
  ranges.clear();
  float lo = 1e30f, hi = 0;
  for (int y = 0; y < image.height_px; ++y) {
    const std::uint8_t* row = image.row(y);
    for (int x = 0; x < image.width_px; ++x) {
      float p[3];
      std::memcpy(p, row + static_cast<std::ptrdiff_t>(x) * 12, sizeof p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      const Vec3 local{p[0], p[1], p[2]};
      entry.cloud_m.push_back(to_f(pose * local));
      const float r = static_cast<float>(std::sqrt(dot(local, local)));
      ranges.push_back(r);
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
  }
  entry.cloud_near_m = ranges.empty() ? 0 : lo;
  entry.cloud_far_m = ranges.empty() ? 0 : hi;
  entry.cloud_colours.reserve(ranges.size());
  for (float r : ranges) {
    const auto c = distance_colour(distance_fraction(r, lo, hi));
    entry.cloud_colours.push_back(IM_COL32(c[0], c[1], c[2], 255));
  }
}

}  // namespace

void sync_camera_images(ViewerState& state) {
  CameraWindowState& cams = state.cameras;
  if (cams.sim == state.sim.get()) return;
  const bool first = cams.sim == nullptr;
  std::set<std::string> shown;
  for (const CameraImage& c : cams.images)
    if (c.shown) shown.insert(c.name);
  cams.images.clear();
  cams.sim = state.sim.get();
  for (const std::string& name : state.sim->image_names()) {
    CameraImage& c = cams.images.emplace_back();
    c.name = name;
    c.view = image_view(state.sim->image(name).format);
    c.shown = first || shown.count(name) > 0;
    if (c.view == ImageView::points) c.sensor = sensor_with_prefix(*state.sim, image_prefix(name));
  }
}

CameraImage* find_camera_image(ViewerState& state, const std::string& name) {
  sync_camera_images(state);
  for (CameraImage& c : state.cameras.images)
    if (c.name == name) return &c;
  return nullptr;
}

void refresh_camera_image(const Simulation& sim, CameraImage& entry) {
  const Image& image = sim.image(entry.name);
  if (image.frame == entry.frame && image.time_s == entry.time_s) return;
  entry.frame = image.frame;
  entry.time_s = image.time_s;
  ++entry.uploads;
  if (entry.view == ImageView::points) {
    rebuild_cloud(sim, image, entry);
    return;
  }
  to_rgb(image, entry.shown_image);
  entry.texture.upload(entry.shown_image.rgb.data(), entry.shown_image.width_px,
                       entry.shown_image.height_px);
}

}  // namespace s2sim::viewer
