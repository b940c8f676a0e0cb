#pragma once
/// \file
/// s2sim-run --video FILE.mp4: a camera's colour image as a video, one video frame per camera
/// frame, at the camera's own rate (measured between its first two frames), through libavcodec
/// (apps/common/video_writer.hpp).

#include "video_writer.hpp"

#include <s2sim/kernel/simulation.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace s2sim::runner {

class CameraVideo {
 public:
  /// The colour image `image_name`, or the scene's only one when it is empty. Throws
  /// s2sim::Error (usage) when there is none, several and none named, or it is not colour.
  CameraVideo(std::string file, const Simulation& sim, const std::string& image_name);
  /// Adds the frame the camera drew since the last call, if any. Throws OutputError when the
  /// file cannot be written.
  void add_new_frame();
  /// Writes what is pending and closes the file; the number of frames written. Throws
  /// OutputError when the file cannot be written.
  int finish();
  const std::string& image_name() const { return name_; }

 private:
  std::string file_, name_;
  const Image* image_ = nullptr;
  std::uint64_t last_frame_ = 0;
  double first_time_s_ = 0;
  std::vector<unsigned char> first_;  ///< held until the second frame gives the rate
  std::optional<apps::VideoWriter> writer_;
  void open(double frame_interval_s);
  void add_frame();
};

}  // namespace s2sim::runner
