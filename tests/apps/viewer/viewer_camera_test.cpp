// The Cameras window on the real s2sim-view under Xvfb, over scenes/camera_lidar: the camera's
// colour image on screen as the camera wrote it, the depth image's legend, opening and
// closing it (no upload while closed or paused), and the scene's images themselves (the
// boxes' body ids, the lidar's cloud).

#include "viewer_harness.hpp"

#include <cmath>
#include <cstdio>
#include <map>

namespace s2sim::viewer_test {
namespace {

const std::string kRgb = "robots/rover/sensors/front/rgb";
const std::string kDepth = "robots/rover/sensors/front/depth";
const std::string kIds = "robots/rover/sensors/front/segmentation";
const std::string kRange = "robots/rover/sensors/lidar/range";
const std::string kPoints = "robots/rover/sensors/lidar/points";

std::string scene() {
  return (kSource / "scenes/camera_lidar").string();
}

/// A `camera-image` line of `print cameras`.
struct Shown {
  int shown = 0;
  unsigned long long frame = 0, uploads = 0;
  double x = 0, y = 0, w = 0, h = 0, near_m = 0, far_m = 0;
  double lx = 0, ly = 0, lw = 0, lh = 0;  ///< the legend's bar
  long points = -1;
};

/// Every `print cameras` of the output, in order, by image name.
std::vector<std::map<std::string, Shown>> camera_prints(const std::string& out) {
  std::vector<std::map<std::string, Shown>> prints(1);
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("camera-images ", 0) == 0) {
      prints.emplace_back();
      continue;
    }
    char name[200];
    Shown s;
    if (std::sscanf(line.c_str(), "camera-image %199s %d %llu %llu points %ld", name, &s.shown,
                    &s.frame, &s.uploads, &s.points) == 5 ||
        std::sscanf(
            line.c_str(),
            "camera-image %199s %d %llu %llu %lf %lf %lf %lf %lf %lf legend %lf %lf %lf %lf", name,
            &s.shown, &s.frame, &s.uploads, &s.x, &s.y, &s.w, &s.h, &s.near_m, &s.far_m, &s.lx,
            &s.ly, &s.lw, &s.lh) == 14)
      prints.back()[name] = s;
  }
  prints.pop_back();  // after the last `camera-images`
  return prints;
}

class CameraWindow : public ViewerRun {};

TEST_F(CameraWindow, ShowsTheCamerasColourImageAsTheCameraWroteIt) {
  const fs::path png = dir_ / "cameras.png";
  const Result r =
      view(scene(), {"--do", "show cameras", "--do", "run-until 0.35", "--do", "wait 3", "--do",
                     "print cameras", "--do", "print image-blocks " + kRgb + " 8 6", "--do",
                     "screenshot " + png.string(), "--do", "quit"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto prints = camera_prints(r.out);
  ASSERT_EQ(prints.size(), 1u) << r.out;
  ASSERT_EQ(prints[0].count(kRgb), 1u) << r.out;
  const Shown& rgb = prints[0].at(kRgb);
  EXPECT_EQ(rgb.shown, 1);
  EXPECT_GE(rgb.frame, 3u);  // 0.1 s frames from t = 0
  ASSERT_GT(rgb.w, 100) << r.out;
  EXPECT_NEAR(rgb.w / rgb.h, 320.0 / 240, 0.02);

  // The image's own mean colour in 8 x 6 blocks against the screen's over the same blocks.
  std::istringstream blocks(r.out.substr(r.out.find("image-blocks ")));
  std::string word, name;
  int nx = 0, ny = 0;
  blocks >> word >> name >> nx >> ny;
  ASSERT_EQ(nx * ny, 48);
  const Image shot = read_png(png);
  ASSERT_EQ(shot.width, 1280);
  double darkest = 255, brightest = 0, worst = 0;
  for (int by = 0; by < ny; ++by)
    for (int bx = 0; bx < nx; ++bx) {
      double want[3];
      blocks >> want[0] >> want[1] >> want[2];
      // The screen pixels whose centres fall inside the block (nearest-pixel sampling).
      double sum[3] = {0, 0, 0};
      int n = 0;
      for (int y = static_cast<int>(std::ceil(rgb.y + rgb.h * by / ny - 0.5));
           y + 0.5 < rgb.y + rgb.h * (by + 1) / ny; ++y)
        for (int x = static_cast<int>(std::ceil(rgb.x + rgb.w * bx / nx - 0.5));
             x + 0.5 < rgb.x + rgb.w * (bx + 1) / nx; ++x, ++n)
          for (int k = 0; k < 3; ++k)
            sum[k] += shot.at(x, y)[k];
      ASSERT_GT(n, 0);
      for (int k = 0; k < 3; ++k) {
        worst = std::max(worst, std::abs(sum[k] / n - want[k]));
        EXPECT_NEAR(sum[k] / n, want[k], 12) << "block " << bx << "," << by << " channel " << k;
      }
      const double l = 0.299 * want[0] + 0.587 * want[1] + 0.114 * want[2];
      darkest = std::min(darkest, l), brightest = std::max(brightest, l);
    }
  // A picture, not a flat colour: sky, floor and boxes.
  EXPECT_GT(brightest - darkest, 40) << "the camera image is nearly uniform";
  std::printf("largest block difference %.1f levels\n", worst);
}

TEST_F(CameraWindow, TheDepthImageHasALegendFromNearToFarAndNoHitIsBlack) {
  const fs::path png = dir_ / "depth.png";
  const Result r =
      view(scene(), {"--do", "show cameras", "--do", "run-until 0.25", "--do", "wait 3", "--do",
                     "print cameras", "--do", "print image-pixel " + kDepth + " 160 2", "--do",
                     "print image-pixel " + kDepth + " 160 235", "--do",
                     "screenshot " + png.string(), "--do", "quit"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto prints = camera_prints(r.out);
  ASSERT_EQ(prints.size(), 1u) << r.out;
  const Shown& depth = prints[0].at(kDepth);
  // The nearest: the floor at the image's bottom edge, 0.36 m under a camera tilted 10 degrees
  // down with a 60-degree view (about 0.5 m along the axis); the farthest within 30 m.
  EXPECT_GT(depth.near_m, 0.3);
  EXPECT_LT(depth.near_m, 0.8);
  EXPECT_GT(depth.far_m, 5);
  EXPECT_LT(depth.far_m, 30);
  EXPECT_NE(r.out.find("image-pixel " + kDepth + " 160 2 inf"), std::string::npos) << r.out;
  ASSERT_GT(depth.lh, 50) << r.out;
  const Image shot = read_png(png);
  // The top row (the sky) black on screen, the bottom (the near floor) warm.
  const unsigned char* sky =
      shot.at(static_cast<int>(depth.x + depth.w / 2), static_cast<int>(depth.y + 1));
  EXPECT_EQ(sky[0] + sky[1] + sky[2], 0);
  const unsigned char* floor =
      shot.at(static_cast<int>(depth.x + depth.w / 2), static_cast<int>(depth.y + depth.h - 2));
  EXPECT_GT(floor[0], floor[2] + 60);
  // The legend's bar: warm at the top (near), blue at the bottom (far).
  const unsigned char* top =
      shot.at(static_cast<int>(depth.lx + depth.lw / 2), static_cast<int>(depth.ly + 2));
  const unsigned char* bottom =
      shot.at(static_cast<int>(depth.lx + depth.lw / 2), static_cast<int>(depth.ly + depth.lh - 3));
  EXPECT_GT(top[0], top[2] + 60);
  EXPECT_GT(bottom[2], bottom[0] + 60);
  // And the lidar's range image has its legend too.
  const Shown& range = prints[0].at(kRange);
  EXPECT_GT(range.near_m, 0.2);
  EXPECT_LT(range.far_m, 20);
  EXPECT_GT(range.lh, 50);
}

TEST_F(CameraWindow, OpensAndClosesAndUploadsOnlyNewFrames) {
  const Result r = view(scene(), {"--do", "wait 2",
                                  "--do", "print cameras",  // closed: nothing
                                  "--do", "show cameras",
                                  "--do", "run-until 0.15",  // open, running
                                  "--do", "wait 5",
                                  "--do", "print cameras",  // paused: no upload
                                  "--do", "wait 20",
                                  "--do", "print cameras",  //
                                  "--do", "hide cameras",
                                  "--do", "run-until 0.45",  // closed, running
                                  "--do", "print cameras",
                                  "--do", "show cameras",  //
                                  "--do", "wait 3",
                                  "--do", "print cameras",  // open again: one
                                  "--do", "camera-image " + kRgb + " off",
                                  "--do", "run-until 0.65",  // not shown
                                  "--do", "wait 2",
                                  "--do", "print cameras",
                                  "--do", "quit"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto p = camera_prints(r.out);
  ASSERT_EQ(p.size(), 6u) << r.out;
  // Closed from the start: nothing uploaded.
  EXPECT_EQ(p[0].at(kRgb).uploads, 0u);
  EXPECT_EQ(p[0].at(kPoints).uploads, 0u);
  // Open while running to 0.15 s: frames at 0 and 0.1 s, one upload each.
  const Shown& a = p[1].at(kRgb);
  EXPECT_EQ(a.frame, 2u);
  EXPECT_EQ(a.uploads, 2u);
  // Paused for 20 more frames: the same frame, no upload.
  EXPECT_EQ(p[2].at(kRgb).uploads, a.uploads);
  EXPECT_EQ(p[2].at(kDepth).uploads, p[1].at(kDepth).uploads);
  // Closed while the camera took frames at 0.2, 0.3 and 0.4 s: still nothing uploaded.
  EXPECT_EQ(p[3].at(kRgb).uploads, a.uploads);
  EXPECT_EQ(p[3].at(kPoints).uploads, p[2].at(kPoints).uploads);
  // Open again: the latest frame, in one upload.
  EXPECT_EQ(p[4].at(kRgb).frame, 5u);
  EXPECT_EQ(p[4].at(kRgb).uploads, a.uploads + 1);
  // An image not shown is not uploaded; the others go on.
  EXPECT_EQ(p[5].at(kRgb).shown, 0);
  EXPECT_EQ(p[5].at(kRgb).uploads, p[4].at(kRgb).uploads);
  EXPECT_GT(p[5].at(kDepth).uploads, p[4].at(kDepth).uploads);
  EXPECT_EQ(p[5].at(kDepth).frame, 7u);
}

TEST_F(CameraWindow, TheSceneSeesItsBoxesAndTheLidarCloudsThem) {
  const Result r =
      view(scene(), {"--do", "show cameras", "--do", "run-until 0.35", "--do", "wait 2", "--do",
                     "print cameras", "--do", "print image-ids " + kIds, "--do", "quit"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::map<std::string, long> pixels;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    char path[200];
    unsigned id = 0;
    long n = 0;
    if (std::sscanf(line.c_str(), ("image-id " + kIds + " %u %ld %199s").c_str(), &id, &n, path) ==
        3)
      pixels[path] = n;
  }
  // The four boxes in front of the camera, each a patch of its own id; the two behind or
  // aside are not seen; floor and sky fill the rest.
  for (const char* box : {"things/red", "things/green", "things/blue", "things/yellow"})
    EXPECT_GT(pixels[box], 200) << box << "\n" << r.out;
  EXPECT_EQ(pixels.count("things/purple"), 0u);
  EXPECT_EQ(pixels.count("things/orange"), 0u);
  EXPECT_GT(pixels["world"], 10000);
  EXPECT_GT(pixels["sky"], 10000);
  // The lidar: 16 x 720 rays, the floor all round within 20 m and the boxes: most hit.
  const auto prints = camera_prints(r.out);
  ASSERT_EQ(prints.size(), 1u);
  EXPECT_GT(prints[0].at(kPoints).points, 16 * 720 / 2);
  EXPECT_LE(prints[0].at(kPoints).points, 16 * 720);
}

}  // namespace
}  // namespace s2sim::viewer_test
