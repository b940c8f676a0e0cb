/// `lidar3d`: a multi-channel scanning range finder (a 3-D lidar, a depth ranger) built on the
/// kernel's ray caster. N channels at evenly spaced elevations times M azimuth steps, all cast
/// at once every period from the sensor frame's pose at the start of the tick. Outputs: the
/// range image `range` (float32, M × N, +infinity where nothing is hit between the minimum
/// and the maximum range), the point cloud `points` (xyz_float32, M × N, in the sensor frame,
/// NaN where nothing is hit), and the signals `hits` and `nearest`. Conventions: azimuth 0
/// along the sensor frame's +X, counter-clockwise about +Z; elevation positive up; row 0 is
/// the highest channel, column 0 the first azimuth step.
#include "kinds.hpp"

#include <cstring>
#include <limits>
#include <string>

namespace s2sim::sensors {

namespace {

/// The period of a lidar without `<period>`: 10 Hz, a spinning lidar's usual rate.
constexpr double kDefaultLidarPeriod_s = 0.1;

/// A finite number (degrees or metres) at `path`, or `fallback` when absent.
double finite(const Params& p, std::string_view path, double fallback) {
  const double v = p.number(path, fallback);
  if (!std::isfinite(v)) fail_at(p, path, "must be a finite number, got " + num(v));
  return v;
}

void store(std::uint8_t* at, float v) {
  std::memcpy(at, &v, sizeof v);
}

}  // namespace

void Lidar3D::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.default_period(ctx, kDefaultLidarPeriod_s);
  s_.schedule(ctx);
  const Params& p = ctx.params();

  // Channels: the rows, elevations evenly spaced from `lowest` to `highest` (degrees).
  rows_ = p.integer_in("channels.count", 16, 1, kMaxImageSide_px);
  const double lowest = finite(p, "channels.lowest", -15);
  const double highest = finite(p, "channels.highest", 15);
  if (lowest < -90 || lowest > 90)
    fail_at(p, "channels.lowest", "must be in -90..90 degrees, got " + num(lowest));
  if (highest < -90 || highest > 90)
    fail_at(p, "channels.highest", "must be in -90..90 degrees, got " + num(highest));
  if (rows_ > 1 && !(lowest < highest))
    fail_at(p, "channels.lowest",
            "must be below highest (" + num(highest) + " degrees) for " + std::to_string(rows_) +
                " channels, got " + num(lowest));
  if (lowest > highest)
    fail_at(p, "channels.lowest",
            "must not be above highest (" + num(highest) + " degrees), got " + num(lowest));

  // Azimuth: the columns, from `start` counter-clockwise to `stop` (degrees). A full turn
  // spaces them by 360/M (the last one short of `stop`, which is `start` again); a partial
  // span includes both ends.
  cols_ = p.integer_in("azimuth.steps", 1800, 1, kMaxImageSide_px);
  const double start = finite(p, "azimuth.start", -180);
  const double stop = finite(p, "azimuth.stop", 180);
  if (!(stop > start) || stop - start > 360 + 1e-9)
    fail_at(p, "azimuth.stop",
            "must be above start (" + num(start) + " degrees) by at most 360 degrees, got " +
                num(stop));
  const bool full_turn = std::abs(stop - start - 360) <= 1e-9;

  if (static_cast<std::int64_t>(rows_) * cols_ > kMaxImagePixels)
    fail_at(p, "azimuth.steps",
            std::to_string(cols_) + " steps of " + std::to_string(rows_) + " channels make " +
                std::to_string(static_cast<std::int64_t>(rows_) * cols_) +
                " rays, past the most pixels of an image (" + std::to_string(kMaxImagePixels) +
                ")");

  // Range (metres): hits nearer than `min` or past `max` read as no hit.
  max_m_ = finite(p, "range.max", 100);
  min_m_ = finite(p, "range.min", 0.1);
  if (!(min_m_ >= 0)) fail_at(p, "range.min", "must be >= 0 m, got " + num(min_m_));
  if (!(max_m_ > min_m_))
    fail_at(p, "range.max", "must be above min (" + num(min_m_) + " m), got " + num(max_m_));

  zig_ = &ziggurat_tables();
  const double deg = kPi / 180;
  for (int y = 0; y < rows_; ++y) {  // row 0 = the highest channel
    const int channel = rows_ - 1 - y;
    const double e =
        rows_ == 1 ? (lowest + highest) / 2 : lowest + (highest - lowest) * channel / (rows_ - 1);
    cos_el_.push_back(std::cos(e * deg));
    sin_el_.push_back(std::sin(e * deg));
  }
  for (int x = 0; x < cols_; ++x) {
    const double a = full_turn   ? start + 360.0 * x / cols_
                     : cols_ > 1 ? start + (stop - start) * x / (cols_ - 1)
                                 : (start + stop) / 2;
    cos_az_.push_back(std::cos(a * deg));
    sin_az_.push_back(std::sin(a * deg));
  }

  range_ = ctx.declare_image("range", cols_, rows_, PixelFormat::float32);
  points_ = ctx.declare_image("points", cols_, rows_, PixelFormat::xyz_float32);
  hits_ = ctx.declare_signal("hits", "1");
  nearest_ = ctx.declare_signal("nearest", "m");
}

void Lidar3D::initialize(StepContext& ctx) {
  ctx.publish(hits_, 0.0);
  ctx.publish(nearest_, -1.0);
}

void Lidar3D::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  const Mat3& rot = w.rotation;
  Image& range = ctx.begin_image(range_);
  Image& points = ctx.begin_image(points_);
  const GenericNoise& n = s_.noise;
  RandomStream random = ctx.random();
  constexpr float kNone = std::numeric_limits<float>::infinity();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  const double* ca = cos_az_.data();
  const double* sa = sin_az_.data();
  int hits = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (int y = 0; y < rows_; ++y) {
    const double ce = cos_el_[static_cast<std::size_t>(y)];
    const double se = sin_el_[static_cast<std::size_t>(y)];
    std::uint8_t* r_row = range.row(y);
    std::uint8_t* p_row = points.row(y);
    for (int x = 0; x < cols_; ++x, r_row += 4, p_row += 12) {
      const Vec3 d{ce * ca[x], ce * sa[x], se};  // the sensor frame
      const RayHit h = ctx.cast_ray(w.position, rot * d, max_m_, s_.ignore);
      if (!h.hit || h.distance_m < min_m_) {
        store(r_row, kNone);
        store(p_row, kNaN);
        store(p_row + 4, kNaN);
        store(p_row + 8, kNaN);
        continue;
      }
      double r = h.distance_m;
      if (n.on) {  // generic noise, on hits only; a range never goes below zero
        double v = n.gain * r + n.offset;
        if (n.stdev > 0) v += n.stdev * ziggurat_normal(random, *zig_);
        if (n.stdev_p > 0) v += n.stdev_p * r * ziggurat_normal(random, *zig_);
        r = v > 0 ? v : 0;
      }
      ++hits;
      if (r < nearest) nearest = r;
      store(r_row, static_cast<float>(r));
      store(p_row, static_cast<float>(r * d.x));
      store(p_row + 4, static_cast<float>(r * d.y));
      store(p_row + 8, static_cast<float>(r * d.z));
    }
  }
  ctx.publish(hits_, static_cast<double>(hits));
  ctx.publish(nearest_, hits > 0 ? nearest : -1.0);
}

}  // namespace s2sim::sensors
