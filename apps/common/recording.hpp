#pragma once
/// \file
/// Recordings (`s2sim-run --record FILE`, docs/recording.md): the whole state of a run at every
/// log period, in a versioned binary format: a text header (the version, how the scene was
/// loaded, the bodies, the signals, the state layout), then one frame per log period with the
/// bodies' poses and twists, every signal and the snapshot (Simulation::save()), all
/// little-endian binary64. The viewer replays one (`s2sim-view --replay FILE`) by restoring the
/// frames' snapshots; python/s2sim/recording.py reads one into numpy arrays.

#include <s2sim/kernel/simulation.hpp>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace s2sim::apps {

inline constexpr char kRecordingMagic[8] = {'S', '2', 'S', 'I', 'M', 'R', 'E', 'C'};
inline constexpr std::uint32_t kRecordingVersion = 1;
inline constexpr char kFrameMarker[4] = {'F', 'R', 'M', 'E'};
inline constexpr char kEndMarker[4] = {'E', 'N', 'D', 'R'};
/// Numbers per body in a frame: position (3) and quaternion w, x, y, z (4); twist: angular (3)
/// and linear (3) velocity, world frame.
inline constexpr std::size_t kPoseNumbers = 7, kTwistNumbers = 6;

/// What the header says: how the scene was loaded (so that a replay loads it again with the
/// same state layout) and what each frame holds.
struct RecordingHeader {
  std::uint32_t version = kRecordingVersion;
  std::string s2sim_version;
  std::string scene;  ///< the scene file, absolute
  double tick_s = 0;
  std::int64_t period_ticks = 1;
  SimulationOptions options;  ///< seed, threads, step, substeps, defines, script, sheet, paths
  std::uint64_t layout = 0;   ///< the snapshot layout's id
  std::vector<std::string> bodies;  ///< scene bodies: robots/<robot>/solids/<id>, things/<id>
  std::vector<SignalInfo> signals;
  std::vector<Simulation::Snapshot::Segment> segments;

  /// The header as written in the file (the text part).
  std::string text() const;
};

/// The header of a simulation loaded with `options`, to record it every `period_ticks`.
RecordingHeader recording_header(const Simulation& sim, const SimulationOptions& options,
                                 std::int64_t period_ticks);

/// Writes a recording. No allocation per frame beyond the snapshot's (Simulation::save()).
class RecordingWriter {
 public:
  /// Creates `file` and writes the header. Throws s2sim::Error (usage) when it cannot.
  RecordingWriter(const std::string& file, const RecordingHeader& header);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// Appends the simulation's state now as a frame; an empty string, or what failed.
  std::string write_frame(const Simulation& sim);
  /// Writes the end record (the frame count) and closes; an empty string, or what failed.
  std::string close();
  std::int64_t frames() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  std::FILE* out_ = nullptr;
  std::string path_;
  std::size_t bodies_ = 0, signals_ = 0;
  std::int64_t frames_ = 0;
  std::vector<unsigned char> buffer_;  ///< the frame's fixed part, reused
};

/// A recording read into memory. Frame k's numbers are rows of the arrays below.
struct Recording {
  std::string file;
  RecordingHeader header;
  std::vector<std::int64_t> ticks;
  std::vector<double> times_s;
  std::vector<double> poses;             ///< per frame, per body: kPoseNumbers
  std::vector<double> twists;            ///< per frame, per body: kTwistNumbers
  std::vector<double> signals;           ///< per frame: one per header signal
  std::vector<std::size_t> state_begin;  ///< frame k's snapshot: states[state_begin[k] ...]
  std::vector<double> states;

  std::size_t frame_count() const { return times_s.size(); }
  std::span<const double> signal_row(std::size_t frame) const {
    return {signals.data() + frame * header.signals.size(), header.signals.size()};
  }
  /// Body `body` (scene body index, 0-based) in frame `frame`.
  Pose pose(std::size_t frame, std::size_t body) const;
  Simulation::Snapshot snapshot(std::size_t frame) const;
  /// The last frame at or before `time_s` (the first one before the start).
  std::size_t frame_at(double time_s) const;
};

/// Reads a recording. Throws s2sim::Error (usage) naming the file and what is wrong: not a
/// recording (another file's magic), a version this build does not read, a malformed header,
/// a frame cut short or the end record missing (truncated), bytes after the end.
Recording read_recording(const std::string& file);

/// Loads the recorded scene (or `scene_override`, when not empty) with the recorded options and
/// checks that it is the recorded one: the same bodies, signals and state layout, else an
/// s2sim::Error (usage) naming the first difference.
std::unique_ptr<Simulation> load_recorded_simulation(const Recording& recording,
                                                     const std::string& scene_override = {});

}  // namespace s2sim::apps
