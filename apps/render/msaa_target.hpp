#pragma once
/// \file
/// A multisampled framebuffer the 3-D view is drawn into, resolved (averaged) into the window's
/// own framebuffer afterwards: smooth edges for the world, while the ImGui panels and the
/// screenshot keep reading an ordinary single-sampled window.

namespace s2sim::render {

class MsaaTarget {
 public:
  MsaaTarget() = default;
  ~MsaaTarget();
  MsaaTarget(const MsaaTarget&) = delete;
  MsaaTarget& operator=(const MsaaTarget&) = delete;

  /// Binds a `samples`-sample colour + depth/stencil framebuffer of width x height pixels,
  /// (re)creating it when the size or sample count changed. False, with nothing bound, when
  /// the driver refuses it (the caller then draws straight into the window).
  bool bind(int width_px, int height_px, int samples);

  /// Averages the samples into `framebuffer` (0: the window's) at (x, y) from its bottom left,
  /// and leaves that framebuffer bound.
  void resolve_into(unsigned framebuffer, int x_px, int y_px) const;

  /// The sample count actually given (the driver may round up), 0 before bind.
  int samples() const { return actual_samples_; }

 private:
  void release();
  unsigned framebuffer_ = 0, color_ = 0, depth_stencil_ = 0;
  int width_px_ = 0, height_px_ = 0, samples_ = 0, actual_samples_ = 0;
  bool failed_ = false;  ///< refused once for this size and count: do not retry every frame
};

}  // namespace s2sim::render
