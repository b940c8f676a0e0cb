/// \file
/// Images that components declare and write (StepContext::begin_image), and the cameras'
/// renderer, which the program running the simulation provides (camera_renderer.hpp).

#include "common/closest_names.hpp"
#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace s2sim {

std::int32_t Simulation::Impl::add_image(const std::string& name, int width_px, int height_px,
                                         PixelFormat format, int component) {
  if (image_index(name) >= 0)
    throw Error(ErrorKind::plugin, "image '" + name + "' is already declared");
  if (bytes_per_pixel(format) == 0)
    throw Error(ErrorKind::plugin, "image '" + name + "': unknown pixel format " +
                                       std::to_string(static_cast<int>(format)));
  if (width_px < 1 || width_px > kMaxImageSide_px || height_px < 1 ||
      height_px > kMaxImageSide_px ||
      static_cast<std::int64_t>(width_px) * height_px > kMaxImagePixels)
    throw Error(ErrorKind::plugin, "image '" + name + "': " + std::to_string(width_px) + " x " +
                                       std::to_string(height_px) + " pixels is outside 1.." +
                                       std::to_string(kMaxImageSide_px) + " per side and " +
                                       std::to_string(kMaxImagePixels) + " in all");
  ImageSlot slot;
  slot.name = name;
  slot.component = component;
  image_slots.push_back(std::move(slot));
  Image image;
  image.width_px = width_px;
  image.height_px = height_px;
  image.format = format;
  image.stride_bytes = width_px * bytes_per_pixel(format);
  images.push_back(image);
  return static_cast<std::int32_t>(images.size() - 1);
}

void Simulation::Impl::bind_images() {
  for (std::size_t i = 0; i < images.size(); ++i) {
    image_slots[i].pixels.assign(images[i].size_bytes(), image_slots[i].blank);
    images[i].data = image_slots[i].pixels.data();
  }
  world.image_count = static_cast<std::int32_t>(images.size());
  world.images = images.data();
  world.renderer = this;
  world.render_camera = &Simulation::Impl::render_camera;
}

void Simulation::Impl::reset_images() {
  for (std::size_t i = 0; i < images.size(); ++i) {
    std::fill(image_slots[i].pixels.begin(), image_slots[i].pixels.end(), image_slots[i].blank);
    images[i].frame = 0;
    images[i].time_s = 0;
  }
}

std::int32_t Simulation::Impl::image_index(std::string_view name) const {
  for (std::size_t i = 0; i < image_slots.size(); ++i)
    if (image_slots[i].name == name) return static_cast<std::int32_t>(i);
  return -1;
}

namespace {

void check_target(const CameraShot& shot, const Image* image, PixelFormat format,
                  const char* what) {
  if (image == nullptr) return;
  if (image->format != format || image->width_px != shot.width_px ||
      image->height_px != shot.height_px || image->data == nullptr)
    throw Error(ErrorKind::runtime,
                std::string("StepContext::render_camera: the ") + what + " image must be " +
                    std::to_string(shot.width_px) + " x " + std::to_string(shot.height_px) +
                    " pixels of format " + std::to_string(static_cast<int>(format)) + ", got " +
                    std::to_string(image->width_px) + " x " + std::to_string(image->height_px) +
                    " of format " + std::to_string(static_cast<int>(image->format)));
}

bool finite_pose(const Pose& p) {
  const Vec3& x = p.position;
  if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return false;
  for (const auto& row : p.rotation.m)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

void Simulation::Impl::render_camera(const void* impl, const CameraShot& shot, Image* rgb,
                                     Image* depth, Image* body_ids) {
  auto& m = *const_cast<Simulation::Impl*>(static_cast<const Simulation::Impl*>(impl));
  if (!finite_pose(shot.pose) || !(shot.vertical_fov_rad > 0) || !(shot.vertical_fov_rad < kPi) ||
      !(shot.near_m > 0) || !(shot.far_m > shot.near_m) || !std::isfinite(shot.far_m) ||
      shot.width_px < 1 || shot.height_px < 1)
    throw Error(ErrorKind::runtime,
                "StepContext::render_camera: a shot needs a finite pose, a field of view in "
                "(0, 180) degrees, 0 < near < far (finite) and a size of at least 1 x 1 pixel");
  check_target(shot, rgb, PixelFormat::rgb8, "colour");
  check_target(shot, depth, PixelFormat::float32, "depth");
  check_target(shot, body_ids, PixelFormat::uint16, "body id");
  if (!m.renderer) {
    if (!m.renderer_error.empty()) throw Error(ErrorKind::runtime, m.renderer_error);
    if (!m.renderer_factory)
      throw Error(ErrorKind::runtime,
                  "no renderer draws this simulation's cameras: s2sim-run, s2sim-view and the "
                  "Python module provide one; a program embedding the kernel gives its own "
                  "(Simulation::set_camera_renderer, docs/embedding.md)");
    try {
      m.renderer = m.renderer_factory(*m.facade);
    } catch (const Error& e) {
      m.renderer_error = std::string("the cameras' renderer could not start: ") + e.what();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      m.renderer_error = std::string("the cameras' renderer could not start: ") + e.what();
    }
    if (!m.renderer) {
      if (m.renderer_error.empty()) m.renderer_error = "the cameras' renderer factory gave none";
      throw Error(ErrorKind::runtime, m.renderer_error);
    }
  }
  m.renderer->render(shot, m.poses.data(), static_cast<int>(m.poses.size()), rgb, depth, body_ids);
}

// --- the façade ------------------------------------------------------------------------------

std::vector<std::string> Simulation::image_names() const {
  std::vector<std::string> names;
  for (const auto& slot : impl_->image_slots)
    names.push_back(slot.name);
  return names;
}

const Image& Simulation::image(std::string_view full_name) const {
  const std::int32_t i = impl_->image_index(full_name);
  if (i < 0)
    throw Error(ErrorKind::usage, common::unknown_name_message("image", full_name, image_names()));
  return impl_->images[static_cast<std::size_t>(i)];
}

void Simulation::set_camera_renderer(CameraRendererFactory factory) {
  impl_->renderer.reset();
  impl_->renderer_error.clear();
  impl_->renderer_factory = std::move(factory);
}

}  // namespace s2sim
