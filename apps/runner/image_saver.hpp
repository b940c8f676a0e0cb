#pragma once
/// \file
/// s2sim-run --save-images DIR: every new frame of every image the components declare (a
/// camera's colour, depth and segmentation, a lidar's range image), as
/// `DIR/<image name>/<frame>.png` (apps/common/image_files.hpp for the pixel formats).

#include <s2sim/kernel/simulation.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace s2sim::runner {

class ImageSaver {
 public:
  /// Makes the folders; throws OutputError when it cannot. Images a PNG cannot hold (point
  /// clouds) are listed in `skipped`.
  ImageSaver(const std::filesystem::path& dir, const Simulation& sim);
  /// Writes the frames drawn since the last call; throws OutputError when one cannot be.
  void save_new_frames();
  const std::vector<std::string>& skipped() const { return skipped_; }
  std::int64_t files_written() const { return written_; }

 private:
  struct Saved {
    const Image* image;
    std::filesystem::path folder;
    std::uint64_t last_frame = 0;
  };
  std::vector<Saved> saved_;
  std::vector<std::string> skipped_;
  std::int64_t written_ = 0;
};

}  // namespace s2sim::runner
