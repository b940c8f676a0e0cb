// The UI script's commands of the Cameras window (ui_script.hpp).
#include "ui_script.hpp"
#include "windows/camera_images.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

namespace s2sim::viewer {
namespace {

Error bad(const std::string& command, const std::string& why) {
  return Error(ErrorKind::usage, "script command '" + command + "': " + why);
}

void print_pixel(ViewerState& state, const std::string& args_text) {
  std::istringstream args(args_text);
  std::string name;
  int x = -1, y = -1;
  if (!(args >> name >> x >> y)) throw bad("print image-pixel " + args_text, "NAME X Y");
  if (find_camera_image(state, name) == nullptr)
    throw bad("print image-pixel " + args_text, "no such image");
  const Image& image = state.sim->image(name);
  if (x < 0 || y < 0 || x >= image.width_px || y >= image.height_px)
    throw bad("print image-pixel " + args_text, "outside the image");
  std::printf("image-pixel %s %d %d", name.c_str(), x, y);
  switch (image_view(image.format)) {
    case ImageView::colour: {
      const std::uint8_t* p = image.row(y) + 3 * x;
      std::printf(" %d %d %d\n", p[0], p[1], p[2]);
      break;
    }
    case ImageView::distance:
      std::printf(" %.6g\n", distance_at(image, x, y));
      break;
    case ImageView::ids: {
      const std::uint16_t id = id_at(image, x, y);
      std::printf(" %u %s\n", id,
                  id == kNoBodyId ? "sky"
                  : static_cast<int>(id) < state.sim->body_count()
                      ? state.sim->body_path(id).c_str()
                      : "?");
      break;
    }
    case ImageView::points: {
      float p[3];
      std::memcpy(p, image.row(y) + 12 * x, sizeof p);
      std::printf(" %.6g %.6g %.6g\n", p[0], p[1], p[2]);
      break;
    }
  }
}

/// The image's mean colour (its displayed RGB8) over an NX x NY grid of blocks, row by row.
void print_blocks(ViewerState& state, const std::string& args_text) {
  std::istringstream args(args_text);
  std::string name;
  int nx = 0, ny = 0;
  if (!(args >> name >> nx >> ny) || nx < 1 || ny < 1)
    throw bad("print image-blocks " + args_text, "NAME NX NY");
  if (find_camera_image(state, name) == nullptr)
    throw bad("print image-blocks " + args_text, "no such image");
  ShownImage shown;
  to_rgb(state.sim->image(name), shown);
  std::printf("image-blocks %s %d %d", name.c_str(), nx, ny);
  for (int by = 0; by < ny; ++by)
    for (int bx = 0; bx < nx; ++bx) {
      double sum[3] = {0, 0, 0};
      int n = 0;
      for (int y = by * shown.height_px / ny; y < (by + 1) * shown.height_px / ny; ++y)
        for (int x = bx * shown.width_px / nx; x < (bx + 1) * shown.width_px / nx; ++x, ++n)
          for (int k = 0; k < 3; ++k)
            sum[k] += shown.rgb[(static_cast<std::size_t>(y) * shown.width_px + x) * 3 + k];
      n = std::max(n, 1);
      std::printf(" %.1f %.1f %.1f", sum[0] / n, sum[1] / n, sum[2] / n);
    }
  std::printf("\n");
}

/// The body ids an ids image holds, each with its pixel count and body path.
void print_ids(ViewerState& state, const std::string& name) {
  if (find_camera_image(state, name) == nullptr)
    throw bad("print image-ids " + name, "no such image");
  const Image& image = state.sim->image(name);
  if (image_view(image.format) != ImageView::ids)
    throw bad("print image-ids " + name, "not a body-id image");
  std::map<std::uint16_t, long> count;
  for (int y = 0; y < image.height_px; ++y)
    for (int x = 0; x < image.width_px; ++x)
      ++count[id_at(image, x, y)];
  for (const auto& [id, n] : count)
    std::printf("image-id %s %u %ld %s\n", name.c_str(), id, n,
                id == kNoBodyId                                  ? "sky"
                : static_cast<int>(id) < state.sim->body_count() ? state.sim->body_path(id).c_str()
                                                                 : "?");
}

}  // namespace

bool camera_command(ViewerState& state, const std::string& command, const std::string& rest) {
  if (command != "camera-image") return false;
  std::istringstream args(rest);
  std::string name, on_off;
  if (!(args >> name >> on_off) || (on_off != "on" && on_off != "off"))
    throw bad(command + " " + rest, "camera-image NAME on|off");
  CameraImage* c = find_camera_image(state, name);
  if (c == nullptr) throw bad(command + " " + rest, "no such image");
  c->shown = on_off == "on";
  return true;
}

bool print_camera(ViewerState& state, const std::string& what) {
  if (what.rfind("image-pixel ", 0) == 0) {
    print_pixel(state, what.substr(12));
    return true;
  }
  if (what.rfind("image-blocks ", 0) == 0) {
    print_blocks(state, what.substr(13));
    return true;
  }
  if (what.rfind("image-ids ", 0) == 0) {
    print_ids(state, what.substr(10));
    return true;
  }
  if (what != "cameras") return false;
  sync_camera_images(state);
  for (const CameraImage& c : state.cameras.images) {
    const unsigned long long frame = c.frame == ~std::uint64_t{0} ? 0 : c.frame;
    std::printf("camera-image %s %d %llu %llu", c.name.c_str(), c.shown ? 1 : 0, frame,
                static_cast<unsigned long long>(c.uploads));
    if (c.view == ImageView::points)
      std::printf(" points %zu\n", c.cloud_m.size());
    else
      std::printf(" %.1f %.1f %.1f %.1f %.4f %.4f legend %.1f %.1f %.1f %.1f\n", c.drawn.x,
                  c.drawn.y, c.drawn.width, c.drawn.height, c.shown_image.near_m,
                  c.shown_image.far_m, c.legend.x, c.legend.y, c.legend.width, c.legend.height);
  }
  std::printf("camera-images %zu\n", state.cameras.images.size());
  return true;
}

}  // namespace s2sim::viewer
