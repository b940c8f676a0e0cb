#include "camera_video.hpp"

#include "outputs.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace s2sim::runner {

namespace {
/// The rate of a video whose camera drew only one frame.
constexpr double kOneFrameInterval_s = 0.04;
}  // namespace

CameraVideo::CameraVideo(std::string file, const Simulation& sim, const std::string& image_name)
    : file_(std::move(file)), name_(image_name) {
  if (name_.empty()) {
    std::vector<std::string> colour;
    for (const std::string& n : sim.image_names())
      if (sim.image(n).format == PixelFormat::rgb8) colour.push_back(n);
    if (colour.empty())
      throw Error(ErrorKind::usage, "--video '" + file_ + "': the scene has no camera image");
    if (colour.size() > 1) {
      std::string list;
      for (const std::string& n : colour)
        list += (list.empty() ? "" : ", ") + n;
      throw Error(ErrorKind::usage, "--video '" + file_ +
                                        "': the scene has several camera images; name one with "
                                        "--video-image (" +
                                        list + ")");
    }
    name_ = colour.front();
  }
  image_ = &sim.image(name_);  // throws naming close names
  if (image_->format != PixelFormat::rgb8)
    throw Error(ErrorKind::usage,
                "--video-image '" + name_ + "' is not a colour image (a video needs rgb8)");
  last_frame_ = image_->frame;
}

void CameraVideo::open(double frame_interval_s) {
  const int fps = std::max(1, static_cast<int>(std::lround(1 / frame_interval_s)));
  writer_.emplace(file_, image_->width_px, image_->height_px, fps);
  writer_->add_frame_rows(first_.data(), 3 * image_->width_px);
}

void CameraVideo::add_new_frame() {
  if (image_->frame == last_frame_) return;
  try {
    add_frame();
  } catch (const Error& e) {
    throw OutputError(e.what());  // the file, not the simulation, failed
  }
}

void CameraVideo::add_frame() {
  last_frame_ = image_->frame;
  if (writer_) {
    writer_->add_frame_rows(image_->data, image_->stride_bytes);
    return;
  }
  if (first_.empty()) {
    first_time_s_ = image_->time_s;
    first_.resize(static_cast<std::size_t>(image_->width_px) * 3 * image_->height_px);
    for (int y = 0; y < image_->height_px; ++y)
      std::copy_n(image_->row(y), 3 * image_->width_px, first_.data() + 3 * y * image_->width_px);
    return;
  }
  open(image_->time_s - first_time_s_);
  writer_->add_frame_rows(image_->data, image_->stride_bytes);
}

int CameraVideo::finish() {
  try {
    if (!writer_ && !first_.empty()) open(kOneFrameInterval_s);
    if (!writer_) return 0;
    writer_->finish();
  } catch (const Error& e) {
    throw OutputError(e.what());
  }
  return writer_->frames();
}

}  // namespace s2sim::runner
