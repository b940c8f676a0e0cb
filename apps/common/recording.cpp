#include "recording.hpp"

#include <s2sim/error.hpp>
#include <s2sim/math.hpp>
#include <s2sim/version.hpp>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace s2sim::apps {
namespace {

// Little-endian whatever the host: byte by byte.
void put_u32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void put_u64(unsigned char* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i)
    p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void put_f64(unsigned char* p, double v) {
  put_u64(p, std::bit_cast<std::uint64_t>(v));
}
std::uint32_t get_u32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}
std::uint64_t get_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i)
    v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}
double get_f64(const unsigned char* p) {
  return std::bit_cast<double>(get_u64(p));
}

// A header token: '%', blanks and line breaks as %XX, so that names and paths holding them
// survive the one-item-per-line, blank-separated header.
std::string escape(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == '%' || c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}
bool unescape(const std::string& text, std::string& out) {
  out.clear();
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 2 >= text.size() || !std::isxdigit(static_cast<unsigned char>(text[i + 1])) ||
        !std::isxdigit(static_cast<unsigned char>(text[i + 2])))
      return false;
    out += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
    i += 2;
  }
  return true;
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const char* script_mode_name(ScriptMode m) {
  switch (m) {
    case ScriptMode::off:
      return "off";
    case ScriptMode::control_block:
      return "control_block";
    case ScriptMode::always:
      return "always";
  }
  return "off";
}

std::vector<std::string> body_names(const Simulation& sim) {
  const auto& sc = sim.scene();
  std::vector<std::string> names;
  for (const auto& body : sc.bodies)
    names.push_back(body.robot >= 0 ? "robots/" + sc.robots[body.robot].id + "/solids/" + body.id
                                    : "things/" + body.id);
  return names;
}

Error bad(const std::string& file, const std::string& what) {
  return Error(ErrorKind::usage, Location{file, "", ""}, what);
}

}  // namespace

std::string RecordingHeader::text() const {
  std::string t = "s2sim-recording " + std::to_string(version) + "\n";
  t += "s2sim " + escape(s2sim_version) + "\n";
  t += "scene " + escape(scene) + "\n";
  t += "tick_s " + number(tick_s) + "\n";
  t += "period_ticks " + std::to_string(period_ticks) + "\n";
  t += "numbers binary64-le\n";
  t += "seed " + std::to_string(options.seed) + "\n";
  t += "threads " + std::to_string(options.threads) + "\n";
  if (options.physics_step_s) t += "physics_step_s " + number(*options.physics_step_s) + "\n";
  if (options.substeps) t += "substeps " + std::to_string(*options.substeps) + "\n";
  if (options.simbody_dynamics_only) t += "simbody_dynamics 1\n";
  for (const auto& [name, value] : options.constants)
    t += "define " + escape(name) + " " + number(value) + "\n";
  t += std::string("script_mode ") + script_mode_name(options.script_mode) + "\n";
  if (options.script_file) t += "script_file " + escape(options.script_file->string()) + "\n";
  for (const auto& c : options.sheet_cells)
    t += "sheet " + std::to_string(c.row) + " " + std::to_string(c.col) + " " + escape(c.text) +
         "\n";
  for (const auto& p : options.plugin_path)
    t += "plugin_path " + escape(p.string()) + "\n";
  if (!options.default_plugin_path) t += "default_plugin_path 0\n";
  for (const auto& p : options.model_path)
    t += "model_path " + escape(p.string()) + "\n";
  char layout_hex[24];
  std::snprintf(layout_hex, sizeof layout_hex, "%016" PRIx64, layout);
  t += std::string("layout ") + layout_hex + "\n";
  for (const auto& b : bodies)
    t += "body " + escape(b) + "\n";
  for (const auto& s : signals)
    t += "signal " + escape(s.name) + " " + escape(s.unit) + "\n";
  for (const auto& g : segments)
    t += "segment " + escape(g.name) + " " +
         (g.size == Simulation::Snapshot::Segment::variable ? std::string("variable")
                                                            : std::to_string(g.size)) +
         " " + std::to_string(g.unit) + "\n";
  return t;
}

RecordingHeader recording_header(const Simulation& sim, const SimulationOptions& options,
                                 std::int64_t period_ticks) {
  namespace fs = std::filesystem;
  RecordingHeader h;
  h.s2sim_version = kSdkVersionString;
  h.scene = fs::absolute(sim.scene().file).lexically_normal().string();
  h.tick_s = sim.tick_s();
  h.period_ticks = period_ticks;
  h.options = options;
  // Folders as absolute paths: a replay may start from another working directory.
  for (auto& p : h.options.plugin_path)
    p = fs::absolute(p).lexically_normal();
  for (auto& p : h.options.model_path)
    p = fs::absolute(p).lexically_normal();
  const Simulation::Snapshot snapshot = sim.save();
  h.layout = snapshot.layout;
  h.segments = snapshot.segments;
  h.bodies = body_names(sim);
  for (std::size_t i = 0; i < sim.signal_count(); ++i)
    h.signals.push_back(sim.signal_info(i));
  return h;
}

RecordingWriter::RecordingWriter(const std::string& file, const RecordingHeader& header)
    : path_(file), bodies_(header.bodies.size()), signals_(header.signals.size()) {
  out_ = std::fopen(file.c_str(), "wb");
  if (out_ == nullptr)
    throw Error(ErrorKind::usage, "--record: cannot write '" + file + "': " + std::strerror(errno));
  const std::string text = header.text();
  unsigned char start[16];
  std::memcpy(start, kRecordingMagic, 8);
  put_u32(start + 8, header.version);
  put_u32(start + 12, static_cast<std::uint32_t>(text.size()));
  std::fwrite(start, 1, sizeof start, out_);
  std::fwrite(text.data(), 1, text.size(), out_);
  buffer_.resize(8 + 16 + 8 * (bodies_ * (kPoseNumbers + kTwistNumbers) + signals_));
}

// A run that stops on an error still leaves a readable recording of its frames so far.
RecordingWriter::~RecordingWriter() {
  (void)close();
}

std::string RecordingWriter::write_frame(const Simulation& sim) {
  const Simulation::Snapshot snapshot = sim.save();
  unsigned char* p = buffer_.data();
  std::memcpy(p, kFrameMarker, 4);
  put_u32(p + 4, static_cast<std::uint32_t>(snapshot.values.size()));
  put_u64(p + 8, static_cast<std::uint64_t>(sim.tick()));
  put_f64(p + 16, sim.time_s());
  p += 24;
  for (std::size_t b = 0; b < bodies_; ++b) {
    const Pose& pose = sim.body_pose(static_cast<int>(b) + 1);
    const Quat q = to_quat(pose.rotation);
    for (double v : {pose.position.x, pose.position.y, pose.position.z, q.w, q.x, q.y, q.z}) {
      put_f64(p, v);
      p += 8;
    }
  }
  for (std::size_t b = 0; b < bodies_; ++b) {
    const Twist& t = sim.body_twist(static_cast<int>(b) + 1);
    for (double v : {t.angular_rad_s.x, t.angular_rad_s.y, t.angular_rad_s.z, t.linear_m_s.x,
                     t.linear_m_s.y, t.linear_m_s.z}) {
      put_f64(p, v);
      p += 8;
    }
  }
  for (std::size_t s = 0; s < signals_; ++s) {
    put_f64(p, sim.signal(s));
    p += 8;
  }
  std::fwrite(buffer_.data(), 1, buffer_.size(), out_);
  // The snapshot in place: on a little-endian host its doubles are already the file's bytes.
  if constexpr (std::endian::native == std::endian::little) {
    std::fwrite(snapshot.values.data(), sizeof(double), snapshot.values.size(), out_);
  } else {
    unsigned char bytes[8];
    for (double v : snapshot.values) {
      put_f64(bytes, v);
      std::fwrite(bytes, 1, 8, out_);
    }
  }
  ++frames_;
  if (std::ferror(out_)) return "--record: writing '" + path_ + "' failed";
  return {};
}

std::string RecordingWriter::close() {
  if (out_ == nullptr) return {};
  unsigned char end[16];
  std::memcpy(end, kEndMarker, 4);
  put_u32(end + 4, 0);
  put_u64(end + 8, static_cast<std::uint64_t>(frames_));
  std::fwrite(end, 1, sizeof end, out_);
  const bool failed = std::ferror(out_) != 0;
  const bool closed = std::fclose(out_) == 0;
  out_ = nullptr;
  if (failed || !closed) return "--record: writing '" + path_ + "' failed";
  return {};
}

Pose Recording::pose(std::size_t frame, std::size_t body) const {
  const double* p = poses.data() + (frame * header.bodies.size() + body) * kPoseNumbers;
  return {{p[0], p[1], p[2]}, to_matrix(Quat{p[3], p[4], p[5], p[6]})};
}

Simulation::Snapshot Recording::snapshot(std::size_t frame) const {
  Simulation::Snapshot s;
  s.layout = header.layout;
  s.segments = header.segments;
  const std::size_t end = frame + 1 < state_begin.size() ? state_begin[frame + 1] : states.size();
  s.values.assign(states.begin() + static_cast<long>(state_begin[frame]),
                  states.begin() + static_cast<long>(end));
  return s;
}

std::size_t Recording::frame_at(double time_s) const {
  // Half a tick of slack: a time read from a frame finds that frame.
  const double t = time_s + 0.5 * header.tick_s;
  const auto it = std::upper_bound(times_s.begin(), times_s.end(), t);
  return it == times_s.begin() ? 0 : static_cast<std::size_t>(it - times_s.begin()) - 1;
}

namespace {

void parse_header(const std::string& file, const std::string& text, RecordingHeader& h) {
  std::istringstream lines(text);
  std::string line;
  int number_of_line = 0;
  bool saw_layout = false, saw_scene = false;
  while (std::getline(lines, line)) {
    ++number_of_line;
    std::vector<std::string> words;
    std::istringstream ws(line);
    for (std::string w; ws >> w;) {
      std::string plain;
      if (!unescape(w, plain))
        throw bad(file,
                  "header line " + std::to_string(number_of_line) + ": bad escape in '" + w + "'");
      words.push_back(plain);
    }
    auto fail = [&](const std::string& why) {
      return bad(file,
                 "header line " + std::to_string(number_of_line) + " ('" + line + "'): " + why);
    };
    auto need = [&](std::size_t n) {
      if (words.size() < n + 1) throw fail("expected " + std::to_string(n) + " value(s)");
    };
    auto to_int = [&](const std::string& w) {
      char* end = nullptr;
      errno = 0;
      const long long v = std::strtoll(w.c_str(), &end, 10);
      if (w.empty() || *end != '\0' || errno == ERANGE) throw fail("'" + w + "' is not an integer");
      return v;
    };
    auto to_double = [&](const std::string& w) {
      char* end = nullptr;
      const double v = std::strtod(w.c_str(), &end);
      if (w.empty() || *end != '\0') throw fail("'" + w + "' is not a number");
      return v;
    };
    if (words.empty()) continue;
    const std::string& key = words[0];
    if (number_of_line == 1) {
      if (key != "s2sim-recording" || words.size() != 2 ||
          to_int(words[1]) != static_cast<long long>(h.version))
        throw fail("expected 's2sim-recording " + std::to_string(h.version) + "'");
    } else if (key == "s2sim") {
      need(1);
      h.s2sim_version = words[1];
    } else if (key == "scene") {
      need(1);
      h.scene = words[1];
      saw_scene = true;
    } else if (key == "tick_s") {
      need(1);
      h.tick_s = to_double(words[1]);
      if (!(h.tick_s > 0)) throw fail("the tick must be positive");
    } else if (key == "period_ticks") {
      need(1);
      h.period_ticks = to_int(words[1]);
      if (h.period_ticks < 1) throw fail("the period must be at least one tick");
    } else if (key == "numbers") {
      need(1);
      if (words[1] != "binary64-le") throw fail("numbers other than binary64-le are not read");
    } else if (key == "seed") {
      need(1);
      h.options.seed = static_cast<std::uint64_t>(to_int(words[1]));
    } else if (key == "threads") {
      need(1);
      h.options.threads = static_cast<int>(to_int(words[1]));
    } else if (key == "physics_step_s") {
      need(1);
      h.options.physics_step_s = to_double(words[1]);
    } else if (key == "substeps") {
      need(1);
      h.options.substeps = static_cast<int>(to_int(words[1]));
    } else if (key == "simbody_dynamics") {
      h.options.simbody_dynamics_only = true;
    } else if (key == "define") {
      need(2);
      h.options.constants.emplace_back(words[1], to_double(words[2]));
    } else if (key == "script_mode") {
      need(1);
      if (words[1] == "off")
        h.options.script_mode = ScriptMode::off;
      else if (words[1] == "control_block")
        h.options.script_mode = ScriptMode::control_block;
      else if (words[1] == "always")
        h.options.script_mode = ScriptMode::always;
      else
        throw fail("unknown script mode");
    } else if (key == "script_file") {
      need(1);
      h.options.script_file = words[1];
    } else if (key == "sheet") {
      need(2);
      h.options.sheet_cells.push_back({static_cast<int>(to_int(words[1])),
                                       static_cast<int>(to_int(words[2])),
                                       words.size() > 3 ? words[3] : std::string()});
    } else if (key == "plugin_path") {
      need(1);
      h.options.plugin_path.emplace_back(words[1]);
    } else if (key == "default_plugin_path") {
      h.options.default_plugin_path = false;
    } else if (key == "model_path") {
      need(1);
      h.options.model_path.emplace_back(words[1]);
    } else if (key == "layout") {
      need(1);
      char* end = nullptr;
      h.layout = std::strtoull(words[1].c_str(), &end, 16);
      if (words[1].empty() || *end != '\0') throw fail("the layout id is not hexadecimal");
      saw_layout = true;
    } else if (key == "body") {
      need(1);
      h.bodies.push_back(words[1]);
    } else if (key == "signal") {
      need(1);
      h.signals.push_back({words[1], words.size() > 2 ? words[2] : std::string()});
    } else if (key == "segment") {
      need(3);
      Simulation::Snapshot::Segment g;
      g.name = words[1];
      g.size = words[2] == "variable" ? Simulation::Snapshot::Segment::variable
                                      : static_cast<std::size_t>(to_int(words[2]));
      g.unit = static_cast<std::size_t>(to_int(words[3]));
      if (g.unit == 0) throw fail("a segment's unit must be at least 1");
      h.segments.push_back(g);
    }
    // Other keys: a later version's additions that change nothing this one reads.
  }
  if (number_of_line == 0) throw bad(file, "the header is empty");
  if (!saw_scene || !saw_layout || h.tick_s <= 0)
    throw bad(file, "the header lacks the scene, the tick or the layout");
}

}  // namespace

Recording read_recording(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw bad(file, std::string("cannot read the recording: ") + std::strerror(errno));
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  Recording r;
  r.file = file;
  const std::size_t size = bytes.size();
  if (size < 16 || std::memcmp(bytes.data(), kRecordingMagic, 8) != 0)
    throw bad(file,
              "not an S2Sim recording (it does not start with 'S2SIMREC'; s2sim-run "
              "--record writes one)");
  const std::uint32_t version = get_u32(bytes.data() + 8);
  if (version != kRecordingVersion)
    throw bad(file, "recording format version " + std::to_string(version) + "; this S2Sim (" +
                        kSdkVersionString + ") reads version " + std::to_string(kRecordingVersion));
  const std::size_t text_size = get_u32(bytes.data() + 12);
  if (16 + text_size > size)
    throw bad(file, "truncated: the header says " + std::to_string(text_size) +
                        " bytes of text, the file ends after " + std::to_string(size - 16));
  parse_header(file,
               std::string(bytes.begin() + 16, bytes.begin() + 16 + static_cast<long>(text_size)),
               r.header);

  const std::size_t nb = r.header.bodies.size(), ns = r.header.signals.size();
  const std::size_t fixed = 8 + 16 + 8 * (nb * (kPoseNumbers + kTwistNumbers) + ns);
  std::size_t at = 16 + text_size;
  bool ended = false;
  while (at < size) {
    const std::string frame_name = "frame " + std::to_string(r.frame_count());
    if (size - at < 16)
      throw bad(file, "truncated: " + std::to_string(size - at) + " bytes after " +
                          std::to_string(r.frame_count()) + " frames, at byte " +
                          std::to_string(at) + " (a frame or the end record needs 16 or more)");
    const unsigned char* p = bytes.data() + at;
    if (std::memcmp(p, kEndMarker, 4) == 0) {
      const std::uint64_t count = get_u64(p + 8);
      if (count != r.frame_count())
        throw bad(file, "the end record counts " + std::to_string(count) +
                            " frames, the file holds " + std::to_string(r.frame_count()));
      at += 16;
      ended = true;
      break;
    }
    if (std::memcmp(p, kFrameMarker, 4) != 0)
      throw bad(file, "byte " + std::to_string(at) + ": " + frame_name +
                          " does not start with 'FRME' (a damaged file)");
    const std::size_t state_count = get_u32(p + 4);
    const std::size_t need = fixed + 8 * state_count;
    if (size - at < need)
      throw bad(file, "truncated: " + frame_name + " at byte " + std::to_string(at) + " needs " +
                          std::to_string(need) + " bytes, the file ends after " +
                          std::to_string(size - at));
    r.ticks.push_back(static_cast<std::int64_t>(get_u64(p + 8)));
    r.times_s.push_back(get_f64(p + 16));
    const unsigned char* q = p + 24;
    for (std::size_t i = 0; i < nb * kPoseNumbers; ++i, q += 8)
      r.poses.push_back(get_f64(q));
    for (std::size_t i = 0; i < nb * kTwistNumbers; ++i, q += 8)
      r.twists.push_back(get_f64(q));
    for (std::size_t i = 0; i < ns; ++i, q += 8)
      r.signals.push_back(get_f64(q));
    r.state_begin.push_back(r.states.size());
    for (std::size_t i = 0; i < state_count; ++i, q += 8)
      r.states.push_back(get_f64(q));
    if (r.frame_count() > 1 && !(r.times_s.back() > r.times_s[r.frame_count() - 2]))
      throw bad(file, frame_name + ": its time " + number(r.times_s.back()) +
                          " s is not after the previous frame's");
    at += need;
  }
  if (!ended)
    throw bad(file, "truncated: the end record is missing after " +
                        std::to_string(r.frame_count()) +
                        " frames (the recording run did not finish writing it)");
  if (at != size) throw bad(file, std::to_string(size - at) + " bytes after the end record");
  if (r.frame_count() == 0) throw bad(file, "the recording holds no frame");
  return r;
}

std::unique_ptr<Simulation> load_recorded_simulation(const Recording& rec,
                                                     const std::string& scene_override) {
  const RecordingHeader& h = rec.header;
  const std::string scene = scene_override.empty() ? h.scene : scene_override;
  std::error_code ec;
  if (scene_override.empty() && !std::filesystem::exists(scene, ec))
    throw bad(rec.file, "the recorded scene '" + scene +
                            "' is not there (moved, or recorded on another machine): name it, "
                            "s2sim-view SCENE --replay FILE");
  auto sim = Simulation::load(scene, h.options);
  auto differs = [&](const std::string& what) {
    return bad(rec.file, "the scene '" + scene + "' is not the recorded one: " + what +
                             " (the scene or S2Sim changed since the recording)");
  };
  const std::vector<std::string> bodies = body_names(*sim);
  if (bodies.size() != h.bodies.size())
    throw differs(std::to_string(h.bodies.size()) + " bodies recorded, " +
                  std::to_string(bodies.size()) + " here");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i] != h.bodies[i])
      throw differs("body " + std::to_string(i) + " is '" + h.bodies[i] + "' there, '" + bodies[i] +
                    "' here");
  if (sim->signal_count() != h.signals.size())
    throw differs(std::to_string(h.signals.size()) + " signals recorded, " +
                  std::to_string(sim->signal_count()) + " here");
  for (std::size_t i = 0; i < h.signals.size(); ++i)
    if (sim->signal_info(i).name != h.signals[i].name)
      throw differs("signal " + std::to_string(i) + " is '" + h.signals[i].name + "' there, '" +
                    sim->signal_info(i).name + "' here");
  if (std::abs(sim->tick_s() - h.tick_s) > 1e-15)
    throw differs("the tick is " + number(h.tick_s) + " s there, " + number(sim->tick_s()) +
                  " s here");
  const Simulation::Snapshot here = sim->save();
  if (here.layout != h.layout) {
    auto describe = [](const std::vector<Simulation::Snapshot::Segment>& v, std::size_t i) {
      if (i >= v.size()) return std::string("absent");
      return "'" + v[i].name + "' (" +
             (v[i].size == Simulation::Snapshot::Segment::variable ? std::string("variable")
                                                                   : std::to_string(v[i].size)) +
             ")";
    };
    std::string first = "the state layout differs";
    for (std::size_t i = 0; i < std::max(here.segments.size(), h.segments.size()); ++i) {
      if (describe(h.segments, i) == describe(here.segments, i)) continue;
      first += ": segment " + std::to_string(i) + " is " + describe(h.segments, i) + " there, " +
               describe(here.segments, i) + " here";
      break;
    }
    throw differs(first);
  }
  return sim;
}

}  // namespace s2sim::apps
