// The recording format (apps/common/recording.hpp, docs/recording.md): a run written frame by
// frame and read back holds the run's poses, twists, signals and snapshots; replaying it by
// restoring each frame's snapshot gives the recorded poses at every frame; bad files are
// refused naming the file and what is wrong.
#include "common/temp_dir.hpp"

#include <recording.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace s2sim::apps {
namespace {

namespace fs = std::filesystem;
const fs::path kNxt = fs::path(S2SIM_SOURCE_DIR) / "scenes" / "nxt";

std::vector<char> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void write_bytes(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<long>(bytes.size()));
}

class RecordingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        test::process_temp_dir() / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir_);
  }

  /// scenes/nxt driven in a curve for `duration_s`, recorded every `period_ticks`; the poses
  /// of every body at every recorded tick, as the run had them.
  std::vector<std::vector<Pose>> record(const fs::path& file, double duration_s,
                                        std::int64_t period_ticks) {
    SimulationOptions options;
    auto sim = Simulation::load(kNxt, options);
    sim->set_input("robots/nxt/axes/left/ref_voltage", 6);
    sim->set_input("robots/nxt/axes/right/ref_voltage", -4);
    RecordingWriter writer(file.string(), recording_header(*sim, options, period_ticks));
    std::vector<std::vector<Pose>> poses;
    auto keep = [&] {
      EXPECT_EQ(writer.write_frame(*sim), "");
      poses.emplace_back();
      for (int b = 1; b < sim->body_count(); ++b)
        poses.back().push_back(sim->body_pose(b));
    };
    keep();
    const auto ticks = std::llround(duration_s / sim->tick_s());
    for (std::int64_t done = 0; done < ticks; done += period_ticks) {
      sim->step(period_ticks);
      keep();
    }
    EXPECT_EQ(writer.close(), "");
    return poses;
  }

  fs::path dir_;
};

TEST_F(RecordingTest, ReadsBackWhatTheRunHadAndItsHeader) {
  const fs::path file = dir_ / "nxt.s2rec";
  const auto poses = record(file, 0.5, 20);
  const Recording rec = read_recording(file.string());
  ASSERT_EQ(rec.frame_count(), 26u);  // t = 0, 0.02, ..., 0.5
  EXPECT_EQ(rec.header.version, kRecordingVersion);
  EXPECT_EQ(rec.header.period_ticks, 20);
  EXPECT_EQ(fs::path(rec.header.scene), fs::canonical(kNxt / "scene.xml"));
  EXPECT_EQ(rec.header.bodies.front(), "robots/nxt/solids/brick");
  EXPECT_DOUBLE_EQ(rec.times_s.back(), 0.5);
  EXPECT_EQ(rec.ticks.back(), 500);
  auto sim = Simulation::load(kNxt);
  ASSERT_EQ(rec.header.signals.size(), sim->signal_count());
  for (std::size_t k = 0; k < rec.frame_count(); ++k)
    for (std::size_t b = 0; b < rec.header.bodies.size(); ++b) {
      const Pose p = rec.pose(k, b);
      EXPECT_EQ(p.position.x, poses[k][b].position.x);  // binary64: exact
      EXPECT_EQ(p.position.y, poses[k][b].position.y);
      EXPECT_EQ(p.position.z, poses[k][b].position.z);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          EXPECT_NEAR(p.rotation.m[i][j], poses[k][b].rotation.m[i][j], 1e-15);
    }
  // The brick moved and turned: the frames are not all one.
  EXPECT_GT(std::abs(rec.pose(25, 0).position.x - rec.pose(0, 0).position.x), 0.01);
  EXPECT_EQ(rec.frame_at(0.25), 12u);
  EXPECT_EQ(rec.frame_at(0.259), 12u);
  EXPECT_EQ(rec.frame_at(-1), 0u);
  EXPECT_EQ(rec.frame_at(9), 25u);
}

TEST_F(RecordingTest, ReplayingByRestoringGivesTheRecordedPosesAtEveryFrameInAnyOrder) {
  const fs::path file = dir_ / "nxt.s2rec";
  const auto poses = record(file, 0.4, 10);
  const Recording rec = read_recording(file.string());
  auto sim = load_recorded_simulation(rec);
  // Forwards, then backwards, then a jump back and forth: the same frame each time.
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < rec.frame_count(); ++k)
    order.push_back(k);
  for (std::size_t k = rec.frame_count(); k-- > 0;)
    order.push_back(k);
  order.insert(order.end(), {7, 40, 7, 0, 7});
  for (std::size_t k : order) {
    sim->restore(rec.snapshot(k));
    EXPECT_EQ(sim->time_s(), rec.times_s[k]);
    for (int b = 1; b < sim->body_count(); ++b) {
      const Pose& p = sim->body_pose(b);
      const Pose& want = poses[k][static_cast<std::size_t>(b) - 1];
      EXPECT_EQ(p.position.x, want.position.x) << "frame " << k << " body " << b;
      EXPECT_EQ(p.position.y, want.position.y);
      EXPECT_EQ(p.position.z, want.position.z);
      EXPECT_EQ(std::memcmp(&p.rotation, &want.rotation, sizeof want.rotation), 0);
    }
    for (std::size_t s = 0; s < sim->signal_count(); ++s)
      ASSERT_EQ(sim->signal(s), rec.signal_row(k)[s]) << sim->signal_info(s).name;
  }
  // And a restored frame runs on exactly as the recorded run did.
  sim->restore(rec.snapshot(20));
  sim->step(10);
  EXPECT_EQ(sim->body_pose(1).position.x, poses[21][0].position.x);
}

TEST_F(RecordingTest, BadFilesAreRefusedNamingTheFileAndTheFault) {
  const fs::path file = dir_ / "nxt.s2rec";
  record(file, 0.1, 10);
  const std::vector<char> good = read_bytes(file);
  auto refusal = [&](const std::vector<char>& bytes, const char* name) {
    const fs::path bad = dir_ / name;
    write_bytes(bad, bytes);
    try {
      read_recording(bad.string());
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::usage);
      EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
      return std::string(e.what());
    }
    ADD_FAILURE() << name << " was read";
    return std::string();
  };
  // Cut anywhere: in the header, in a frame, before the end record.
  EXPECT_NE(refusal({good.begin(), good.begin() + 40}, "cut_header").find("truncated"),
            std::string::npos);
  EXPECT_NE(refusal({good.begin(), good.end() - 100}, "cut_frame").find("truncated: frame"),
            std::string::npos);
  EXPECT_NE(refusal({good.begin(), good.end() - 16}, "no_end").find("end record is missing"),
            std::string::npos);
  EXPECT_NE(refusal({}, "empty").find("not an S2Sim recording"), std::string::npos);
  const std::string csv = "time [s],x\n0,1\n";
  EXPECT_NE(refusal({csv.begin(), csv.end()}, "foreign.csv").find("not an S2Sim recording"),
            std::string::npos);
  std::vector<char> v2 = good;
  v2[8] = 2;
  EXPECT_NE(refusal(v2, "version2").find("format version 2; this S2Sim"), std::string::npos);
  std::vector<char> extra = good;
  extra.push_back('x');
  EXPECT_NE(refusal(extra, "extra").find("1 bytes after the end record"), std::string::npos);
  std::vector<char> damaged = good;
  const std::string text(good.begin() + 16, good.end());
  const std::size_t second_frame = 16 + text.find("FRME", text.find("FRME") + 4);
  damaged[second_frame] = 'X';
  EXPECT_NE(refusal(damaged, "damaged").find("frame 1 does not start with 'FRME'"),
            std::string::npos);
  EXPECT_THROW(read_recording((dir_ / "absent").string()), Error);
}

TEST_F(RecordingTest, AnotherSceneIsNotTakenForTheRecordedOne) {
  const fs::path file = dir_ / "nxt.s2rec";
  record(file, 0.05, 10);
  Recording rec = read_recording(file.string());
  // The recorded scene moved: a copy given by name is the recorded one.
  fs::copy(kNxt, dir_ / "nxt_moved");
  rec.header.scene = (dir_ / "gone" / "scene.xml").string();
  try {
    load_recorded_simulation(rec);
    FAIL() << "a recording whose scene is gone loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not there"), std::string::npos) << e.what();
  }
  EXPECT_EQ(load_recorded_simulation(rec, (dir_ / "nxt_moved").string())->body_count(),
            static_cast<int>(rec.header.bodies.size()) + 1);
  try {
    load_recorded_simulation(rec, (fs::path(S2SIM_SOURCE_DIR) / "scenes" / "default").string());
    FAIL() << "scenes/default taken for the recorded scenes/nxt";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not the recorded one"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace s2sim::apps
