#pragma once
/// \file
/// An MP4 video written frame by frame through Debian's libavcodec (`s2sim-view --replay FILE
/// --video OUT.mp4`, `s2sim-run --video OUT.mp4`, docs/recording.md): H.264 (libx264) when the
/// library has it, else MPEG-4 part 2, in YUV 4:2:0. A program built without libavcodec
/// refuses `--video` saying so.

#include <memory>
#include <string>

namespace s2sim::apps {

/// Whether this program was built with libavcodec.
bool video_supported();

class VideoWriter {
 public:
  /// Opens `file` for frames of `width_px` x `height_px` (odd sizes lose their last row or
  /// column) at `fps`. Throws s2sim::Error (usage) naming the file and the reason.
  VideoWriter(const std::string& file, int width_px, int height_px, int fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Encodes one frame of RGB pixels, 3 bytes each, rows bottom-up as OpenGL reads them.
  void add_frame(const unsigned char* rgb_bottom_up);
  /// Encodes one frame of RGB pixels, 3 bytes each, from the top row, the next row
  /// `stride_bytes` on (negative: rows bottom-up).
  void add_frame_rows(const unsigned char* top_row, int stride_bytes);
  /// Flushes the encoder and closes the file. Throws s2sim::Error when writing failed.
  void finish();
  int frames() const { return frames_; }
  /// The codec used ("libx264", "mpeg4").
  const std::string& codec() const { return codec_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int frames_ = 0;
  std::string codec_;
};

}  // namespace s2sim::apps
