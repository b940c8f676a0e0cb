// s2sim-view --replay (docs/recording.md) under Xvfb: a recording of s2sim-run --record plays
// with the recorded poses at every frame, a scrub back to t and forward again shows the same
// frame pixel for pixel, it plays backwards, the chart follows the timeline, --video writes an
// MP4 that decodes to the expected frames, and a bad recording is refused naming it.

#include "viewer_harness.hpp"

#ifdef S2SIM_TEST_VIDEO
#include "common/decoded_video.hpp"
#endif

#include <recording.hpp>

namespace s2sim::viewer_test {
namespace {

class Replay : public ViewerRun {
 protected:
  /// scenes/nxt driven in a curve for 1 s, recorded every 20 ms.
  fs::path record() {
    const fs::path file = dir_ / "nxt.s2rec";
    const Result r = ::viewer_test::run(quote(::viewer_test::kRunner.string()) + " " +
                                            quote((kSource / "scenes" / "nxt").string()) +
                                            " --duration 1 --log-period 0.02 --quiet --record " +
                                            quote(file.string()) +
                                            " --set robots/nxt/axes/left/ref_voltage=6"
                                            " robots/nxt/axes/right/ref_voltage=-2",
                                        dir_);
    EXPECT_EQ(r.status, 0) << r.err;
    return file;
  }
  /// s2sim-view --replay FILE with UI script commands.
  Result replay(const fs::path& file, std::vector<std::string> args) {
    args.insert(args.begin(), file.string());
    return view("--replay", args);
  }
  static std::vector<std::string> lines_starting(const std::string& text, const std::string& word) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (line.rfind(word + " ", 0) == 0) out.push_back(line);
    return out;
  }
};

TEST_F(Replay, ShowsTheRecordedPosesAndAScrubBackAndForthGivesTheSameFrame) {
  const fs::path file = record();
  const apps::Recording rec = apps::read_recording(file.string());
  const fs::path a = dir_ / "a.png", b = dir_ / "b.png", c = dir_ / "c.png";
  const Result r = replay(file, {"--paused",
                                 "--show-window",
                                 "chart",
                                 "--chart",
                                 "robots/nxt/x",
                                 "--do",
                                 "replay-seek 0.5",
                                 "--do",
                                 "wait 2",
                                 "--do",
                                 "print replay",
                                 "--do",
                                 "print body brick",
                                 "--do",
                                 "print chart-samples",
                                 "--do",
                                 "screenshot " + a.string(),
                                 "--do",
                                 "replay-seek 0.9",
                                 "--do",
                                 "wait 2",
                                 "--do",
                                 "print body brick",
                                 "--do",
                                 "screenshot " + c.string(),
                                 "--do",
                                 "replay-seek 0.5",
                                 "--do",
                                 "wait 2",
                                 "--do",
                                 "print body brick",
                                 "--do",
                                 "print chart-samples",
                                 "--do",
                                 "screenshot " + b.string(),
                                 "--do",
                                 "quit"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto bodies = lines_starting(r.out, "body");
  ASSERT_EQ(bodies.size(), 3u) << r.out;
  // The recorded pose of the frame at 0.5 s, then at 0.9 s, then at 0.5 s again.
  auto expected = [&](double t) {
    const Pose p = rec.pose(rec.frame_at(t), 0);
    char line[160];
    std::snprintf(line, sizeof line, "body brick %.9f %.9f %.9f", p.position.x, p.position.y,
                  p.position.z);
    return std::string(line);
  };
  EXPECT_EQ(bodies[0], expected(0.5));
  EXPECT_EQ(bodies[1], expected(0.9));
  EXPECT_NE(bodies[1], bodies[0]);  // the robot moved in between
  EXPECT_EQ(bodies[2], expected(0.5));
  const auto replays = lines_starting(r.out, "replay");
  ASSERT_EQ(replays.size(), 1u) << r.out;
  EXPECT_EQ(replays[0], "replay 0.500000000 0.500000000 25 51 0 1");
  // The chart follows the timeline: the samples up to 0.5 s, both times.
  const auto charts = lines_starting(r.out, "chart-samples");
  ASSERT_EQ(charts.size(), 2u) << r.out;
  EXPECT_EQ(charts[0], charts[1]);
  EXPECT_EQ(charts[0].rfind("chart-samples 26 0", 0), 0u) << charts[0];
  // The same frame, pixel for pixel; another frame differs.
  const Image ia = read_png(a), ib = read_png(b), ic = read_png(c);
  ASSERT_EQ(ia.width, 1280);
  ASSERT_EQ(ib.width, 1280);
  EXPECT_TRUE(ia.rgb == ib.rgb) << "the scrub back to 0.5 s shows another picture";
  EXPECT_FALSE(ia.rgb == ic.rgb) << "0.5 s and 0.9 s look the same";
}

TEST_F(Replay, PlaysForwardsAndBackwardsAtItsSpeedAndStopsAtTheEnds) {
  const fs::path file = record();
  // Scripted frames are 1/60 s apart: 30 frames at 2x are 1 s of the recording.
  const Result r = replay(file, {"--do", "replay-seek 0.2",
                                 "--do", "replay-speed 0.6",
                                 "--do", "wait 30",
                                 "--do", "print replay",
                                 "--do", "replay-speed -1.2",
                                 "--do", "wait 15",
                                 "--do", "print replay",
                                 "--do", "replay-speed -3",
                                 "--do", "wait 60",
                                 "--do", "print replay",
                                 "--do", "quit"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = lines_starting(r.out, "replay");
  ASSERT_EQ(lines.size(), 3u) << r.out;
  double clock[3] = {}, frame_time[3] = {};
  int playing[3] = {};
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(std::sscanf(lines[i].c_str(), "replay %lf %lf %*d %*d %d", &clock[i], &frame_time[i],
                          &playing[i]),
              3);
  EXPECT_NEAR(clock[0], 0.2 + 30 * 0.6 / 60, 1e-6);       // 0.5 s
  EXPECT_NEAR(clock[1], clock[0] - 15 * 1.2 / 60, 1e-6);  // back to 0.2 s
  EXPECT_EQ(playing[1], 1);
  EXPECT_EQ(clock[2], 0.0);  // backwards to the start, where it stops
  EXPECT_EQ(playing[2], 0);
  for (int i = 0; i < 3; ++i)
    EXPECT_LE(frame_time[i], clock[i] + 1e-9);
}

TEST_F(Replay, ABadRecordingIsRefusedNamingTheFile) {
  const fs::path file = record();
  std::string bytes = read_file(file);
  const fs::path cut = dir_ / "cut.s2rec";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  Result r = replay(cut, {"--frames", "1"});
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_NE(r.err.find(cut.string() + ": truncated: frame"), std::string::npos) << r.err;
  const fs::path csv = dir_ / "log.csv";
  std::ofstream(csv) << "time [s]\n0\n";
  r = replay(csv, {"--frames", "1"});
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_NE(r.err.find("not an S2Sim recording"), std::string::npos) << r.err;
  r = replay(file, {"--seed", "3", "--frames", "1"});
  EXPECT_EQ(r.status, 4);
  EXPECT_NE(r.err.find("the recording says how its scene is loaded"), std::string::npos) << r.err;
}

#ifdef S2SIM_TEST_VIDEO
using s2sim::test::decode;
using s2sim::test::Decoded;

TEST_F(Replay, ExportsAnMp4ThatDecodesToOneFramePerVideoPeriod) {
  const fs::path file = record();
  const fs::path video = dir_ / "nxt.mp4";
  // 1 s of recording at 25 frames per second: t = 0, 0.04, ..., 1.0.
  const Result r = replay(file, {"--video", video.string(), "--video-fps", "25"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("video " + video.string() + ": 26 frames of 1280x720 at 25 fps"),
            std::string::npos)
      << r.out;
  const Decoded d = decode(video);
  EXPECT_EQ(d.width, 1280);
  EXPECT_EQ(d.height, 720);
  EXPECT_EQ(d.frames, 26) << d.codec << ", " << d.packets << " packets";
  // At half speed, twice the frames.
  const fs::path slow = dir_ / "slow.mp4";
  ASSERT_EQ(
      replay(file, {"--video", slow.string(), "--video-fps", "25", "--speed", "0.5", "--hide-ui"})
          .status,
      0);
  EXPECT_EQ(decode(slow).frames, 51);
}
#endif

}  // namespace
}  // namespace s2sim::viewer_test
