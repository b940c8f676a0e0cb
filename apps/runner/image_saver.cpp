#include "image_saver.hpp"

#include "image_files.hpp"
#include "outputs.hpp"

#include <cstdio>
#include <system_error>

namespace s2sim::runner {

ImageSaver::ImageSaver(const std::filesystem::path& dir, const Simulation& sim) {
  for (const std::string& name : sim.image_names()) {
    const Image& image = sim.image(name);
    if (!apps::png_holds(image.format)) {
      skipped_.push_back(name);
      continue;
    }
    const std::filesystem::path folder = dir / name;
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error)
      throw OutputError("--save-images: cannot make '" + folder.string() + "': " + error.message());
    saved_.push_back({&image, folder, image.frame});
  }
}

void ImageSaver::save_new_frames() {
  for (Saved& s : saved_) {
    if (s.image->frame == s.last_frame) continue;
    s.last_frame = s.image->frame;
    char name[32];
    std::snprintf(name, sizeof name, "%06llu.png", static_cast<unsigned long long>(s.last_frame));
    if (const std::string error = apps::write_png(s.folder / name, *s.image); !error.empty())
      throw OutputError("--save-images: " + error);
    ++written_;
  }
}

}  // namespace s2sim::runner
