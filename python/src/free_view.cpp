// sim.render: the scene as it stands drawn between steps, from a free view (an eye looking at a
// target) or from a camera sensor's pose with its optics, into new NumPy arrays. The cameras
// and these views share one headless renderer (PyRendering).
#include "py_simulation.hpp"

#include <s2sim/kernel/scene.hpp>

#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace s2sim::python {

CameraRenderer& PyRendering::get(const Simulation& sim) {
  if (renderer) return *renderer;
  if (!error.empty()) throw Error(ErrorKind::runtime, error);
  try {
    renderer = render::make_headless_camera_renderer(sim);
  } catch (const std::exception& e) {
    error = std::string("the renderer could not start: ") + e.what();
    throw Error(ErrorKind::runtime, error);
  }
  return *renderer;
}

namespace {

/// What the kernel draws its cameras through: the shared renderer, each shot recorded by the
/// address of the images it fills (the kernel's own, which stay where they are).
class SharedRenderer final : public CameraRenderer {
 public:
  SharedRenderer(std::shared_ptr<PyRendering> rendering, const Simulation& sim)
      : rendering_(std::move(rendering)), sim_(sim) {}

  void render(const CameraShot& shot, const Pose* body_poses, int body_count, Image* rgb,
              Image* depth, Image* body_ids) override {
    const std::lock_guard<std::mutex> lock(rendering_->mutex);
    rendering_->get(sim_).render(shot, body_poses, body_count, rgb, depth, body_ids);
    for (const Image* image : {rgb, depth, body_ids})
      if (image) rendering_->shots[image] = shot;
  }

 private:
  std::shared_ptr<PyRendering> rendering_;
  const Simulation& sim_;
};

[[noreturn]] void refuse(const std::string& argument, const std::string& why) {
  throw Error(ErrorKind::usage, "render(): " + argument + " " + why);
}

Vec3 point(const py::handle& value, const char* argument) {
  std::vector<double> v;
  try {
    v = value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    refuse(argument, "must be three numbers (x, y, z), got " + py::repr(value).cast<std::string>());
  }
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    refuse(argument,
           "must be three finite numbers (x, y, z), got " + py::repr(value).cast<std::string>());
  return {v[0], v[1], v[2]};
}

/// The camera frame (+Z forward, +Y up, +X to the image's left) looking from `eye` at
/// `target` with `up` upward in the image.
Mat3 look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
  const Vec3 forward = target - eye;
  if (!(norm(forward) > 1e-12)) refuse("target", "must differ from eye");
  const Vec3 z = forward * (1 / norm(forward));
  const Vec3 left = cross(up, z);
  if (!(norm(left) > 1e-9 * norm(up))) refuse("up", "must not be along the line of sight");
  const Vec3 x = left * (1 / norm(left));
  const Vec3 y = cross(z, x);
  Mat3 r;
  const Vec3 columns[3] = {x, y, z};
  for (int c = 0; c < 3; ++c) {
    r.m[0][c] = columns[c].x;
    r.m[1][c] = columns[c].y;
    r.m[2][c] = columns[c].z;
  }
  return r;
}

const char* const kOutputs[3] = {"rgb", "depth", "segmentation"};

/// The cameras: the prefixes of the images named <camera>/rgb, /depth or /segmentation.
std::vector<std::string> camera_names(const Simulation& sim) {
  std::vector<std::string> names;
  for (const std::string& image : sim.image_names())
    for (const char* output : kOutputs) {
      const std::string suffix = std::string("/") + output;
      if (image.size() > suffix.size() &&
          image.compare(image.size() - suffix.size(), suffix.size(), suffix) == 0) {
        std::string camera = image.substr(0, image.size() - suffix.size());
        if (names.empty() || names.back() != camera) names.push_back(std::move(camera));
      }
    }
  return names;
}

std::string sensor_path(const scene::Scene& sc, const scene::Sensor& s) {
  return s.robot >= 0
             ? "robots/" + sc.robots[static_cast<std::size_t>(s.robot)].id + "/sensors/" + s.name
             : "sensors/" + s.name;
}

/// The shot of camera `name` as it stands: its optics as it last drew, its pose now.
CameraShot camera_shot(const Simulation& sim, const PyRendering& rendering,
                       const std::string& name) {
  const std::vector<std::string> cameras = camera_names(sim);
  bool known = false;
  for (const auto& c : cameras)
    known = known || c == name;
  if (!known) {
    std::string list;
    for (const auto& c : cameras)
      list += (list.empty() ? "" : ", ") + c;
    refuse("camera", "'" + name + "' is not a camera of this scene (cameras: " +
                         (list.empty() ? std::string("none") : list) + ")");
  }
  const CameraShot* drawn = nullptr;
  for (const char* output : kOutputs) {
    const std::string image = name + "/" + output;
    for (const auto& n : sim.image_names())
      if (n == image) {
        auto it = rendering.shots.find(&sim.image(image));
        if (it != rendering.shots.end()) drawn = &it->second;
      }
  }
  if (!drawn)
    refuse("camera", "'" + name +
                         "' has drawn no frame yet: its optics are known from its first frame "
                         "(step the simulation first)");
  const scene::Scene& sc = sim.scene();
  for (const scene::Sensor& s : sc.sensors)
    if (sensor_path(sc, s) == name) {
      CameraShot shot = *drawn;
      shot.pose = sim.body_pose(s.body + 1) *
                  Pose{s.pose.position, s.pose.rotation * camera_frame_in_sensor()};
      return shot;
    }
  refuse("camera", "'" + name + "' is not a sensor of this scene");
}

double number(const py::handle& value, const char* argument) {
  try {
    return value.cast<double>();
  } catch (const py::cast_error&) {
    refuse(argument, "must be a number, got " + py::repr(value).cast<std::string>());
  }
}

int side(const py::handle& value, const char* argument) {
  const double v = number(value, argument);
  if (!(v >= 1 && v <= kMaxImageSide_px) || v != std::floor(v))
    refuse(argument, "must be a whole number of pixels in 1.." + std::to_string(kMaxImageSide_px) +
                         ", got " + py::repr(value).cast<std::string>());
  return static_cast<int>(v);
}

/// Which outputs, in the order asked: a name or a sequence of names.
std::vector<int> outputs_asked(const py::handle& outputs, bool* single) {
  std::vector<std::string> names;
  *single = py::isinstance<py::str>(outputs);
  try {
    if (*single)
      names.push_back(outputs.cast<std::string>());
    else
      names = outputs.cast<std::vector<std::string>>();
  } catch (const py::cast_error&) {
    refuse("outputs", "must be 'rgb', 'depth', 'segmentation' or a sequence of them, got " +
                          py::repr(outputs).cast<std::string>());
  }
  if (names.empty()) refuse("outputs", "must name at least one of rgb, depth, segmentation");
  std::vector<int> which;
  for (const auto& n : names) {
    int k = -1;
    for (int i = 0; i < 3; ++i)
      if (n == kOutputs[i]) k = i;
    if (k < 0) refuse("outputs", "'" + n + "' is none of rgb, depth, segmentation");
    for (int w : which)
      if (w == k) refuse("outputs", "names '" + n + "' twice");
    which.push_back(k);
  }
  return which;
}

py::object render_view(PySimulation& s, const py::object& camera, const py::object& eye,
                       const py::object& target, const py::object& up, const py::object& fov,
                       const py::object& width, const py::object& height, const py::object& near,
                       const py::object& far, const py::object& outputs) {
  Simulation& sim = s.sim();
  bool single = false;
  const std::vector<int> which = outputs_asked(outputs, &single);
  CameraShot shot;
  if (!camera.is_none()) {
    if (!eye.is_none() || !target.is_none())
      refuse("camera", "takes the camera's pose: give either camera or eye and target");
    if (!py::isinstance<py::str>(camera))
      refuse("camera", "must be a camera's name, got " + py::repr(camera).cast<std::string>());
    shot = camera_shot(sim, s.rendering(), camera.cast<std::string>());
  } else {
    if (eye.is_none() || target.is_none())
      refuse(eye.is_none() ? "eye" : "target",
             "is needed: give camera, or eye and target (points in the world, metres)");
    const Vec3 from = point(eye, "eye");
    shot.pose = Pose{from, look_at(from, point(target, "target"), point(up, "up"))};
    shot.vertical_fov_rad = 60 * kPi / 180;
    shot.near_m = 0.01;
    shot.far_m = 100;
    shot.width_px = 320;
    shot.height_px = 240;
  }
  if (!fov.is_none()) {
    const double deg = number(fov, "fov");
    if (!(deg > 0 && deg < 180))
      refuse("fov", "must be a vertical field of view in (0, 180) degrees, got " +
                        py::repr(fov).cast<std::string>());
    shot.vertical_fov_rad = deg * kPi / 180;
  }
  if (!width.is_none()) shot.width_px = side(width, "width");
  if (!height.is_none()) shot.height_px = side(height, "height");
  if (static_cast<std::int64_t>(shot.width_px) * shot.height_px > kMaxImagePixels)
    refuse("width", "x height must be at most " + std::to_string(kMaxImagePixels) + " pixels");
  if (!near.is_none()) shot.near_m = number(near, "near");
  if (!far.is_none()) shot.far_m = number(far, "far");
  if (!(shot.near_m > 0) || !std::isfinite(shot.near_m))
    refuse("near", "must be a positive distance in metres, got " + std::to_string(shot.near_m));
  if (!(shot.far_m > shot.near_m) || !std::isfinite(shot.far_m))
    refuse("far", "must be finite and beyond near (" + std::to_string(shot.near_m) + " m), got " +
                      std::to_string(shot.far_m));

  // New arrays, and the images over them that the renderer fills.
  const py::ssize_t h = shot.height_px, w = shot.width_px;
  py::array arrays[3];
  Image images[3];
  bool asked[3] = {false, false, false};
  const PixelFormat formats[3] = {PixelFormat::rgb8, PixelFormat::float32, PixelFormat::uint16};
  for (int k : which) {
    asked[k] = true;
    if (k == 0)
      arrays[k] = py::array_t<std::uint8_t>({h, w, py::ssize_t{3}});
    else if (k == 1)
      arrays[k] = py::array_t<float>({h, w});
    else
      arrays[k] = py::array_t<std::uint16_t>({h, w});
    Image& image = images[k];
    image.width_px = shot.width_px;
    image.height_px = shot.height_px;
    image.format = formats[k];
    image.stride_bytes = shot.width_px * bytes_per_pixel(formats[k]);
    image.data = static_cast<std::uint8_t*>(arrays[k].mutable_data());
  }
  auto wanted = [&](int k) { return asked[k] ? &images[k] : nullptr; };
  {
    PySimulation::Exclusive own(s, "render()");
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(s.rendering().mutex);
    const std::vector<Pose>& poses = sim.body_poses();
    s.rendering().get(sim).render(shot, poses.data(), static_cast<int>(poses.size()), wanted(0),
                                  wanted(1), wanted(2));
  }
  if (single) return std::move(arrays[which[0]]);
  py::tuple out(which.size());
  for (std::size_t i = 0; i < which.size(); ++i)
    out[i] = std::move(arrays[which[i]]);
  return out;
}

}  // namespace

CameraRendererFactory shared_renderer_factory(std::shared_ptr<PyRendering> rendering) {
  return [rendering](const Simulation& sim) -> std::unique_ptr<CameraRenderer> {
    const std::lock_guard<std::mutex> lock(rendering->mutex);
    rendering->get(sim);  // the kernel reports the failure of the first frame
    return std::make_unique<SharedRenderer>(rendering, sim);
  };
}

void bind_render(PySimulationClass& cls) {
  cls.def("render", &render_view, py::arg("camera") = py::none(), py::kw_only(),
          py::arg("eye") = py::none(), py::arg("target") = py::none(),
          py::arg("up") = py::make_tuple(0.0, 0.0, 1.0), py::arg("fov") = py::none(),
          py::arg("width") = py::none(), py::arg("height") = py::none(),
          py::arg("near") = py::none(), py::arg("far") = py::none(), py::arg("outputs") = "rgb",
          "The scene as it stands, drawn now into new arrays: from a camera sensor's pose "
          "with its optics (camera='robots/<robot>/sensors/<id>', known once it has drawn a "
          "frame), or from eye looking at target (world points, metres) with up upward in "
          "the image. fov: the vertical field of view in degrees (a free view's default 60); "
          "width, height in pixels (320 x 240); near, far the clipping distances in metres "
          "(0.01, 100). outputs: 'rgb' (H×W×3 uint8), 'depth' (H×W float32, metres along the "
          "optical axis, inf beyond far) or 'segmentation' (H×W uint16 body index, 65535 the "
          "sky), or a sequence of them for a tuple in that order. Given a camera, the other "
          "arguments override its optics. Raises UsageError naming the argument at fault.");
}

}  // namespace s2sim::python
