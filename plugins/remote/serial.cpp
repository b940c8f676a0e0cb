// The `serial` controller: a pseudo-terminal carrying a robot's (or the scene's) inputs and
// signals as text lines, so that firmware written for a serial port talks to the simulated
// robot (docs/remote.md, "Serial link"). In real time, as a serial line is, every control
// period the link reads the complete lines that arrived and writes one line of signals. In
// lock-step it writes the line of signals, then waits (up to wait_s, wall clock) for the
// device's input line before the tick goes on, so a run does not depend on either side's speed.
//
//   simulation -> device, every period:  S <time> <signal 1> ... <signal m>\n
//   device -> simulation:                 I <input 1> ... <input n>\n     (sets the inputs)
//                                         ?\n                             (asks for the names)
//   simulation -> device, after "?":      # s2sim-serial 1\n # input <name> <unit>\n ...
//                                         # signal <name> <unit>\n # end\n
//
// The device's lines may end in LF, CR LF or CR. Numbers are C-locale decimal (%.17g: doubles
// round-trip). A malformed line (not exactly n finite numbers, unknown command, longer than
// 4096 bytes) is dropped and counted. As for the remote link, a device that stops sending for
// timeout_s (real time) or does not answer within wait_s (lock-step) leaves the inputs zeroed. The
// link's bookkeeping stays in members (see remote.cpp: connection, not world state).
#include "kinds.hpp"
#include "link_waits.hpp"
#include "served_set.hpp"

#include <s2sim/sdk.hpp>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

namespace s2sim::links {

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kMaxLine = 4096;
// A flood must not hold the simulation: at most this many reads of the device a period (4 MiB)
// unless a lock-step period is waiting, which its deadline bounds.
constexpr int kMaxReadsPerPeriod = 1024;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

class Serial final : public Component {
 public:
  ~Serial() override {
    // Closing our ends hangs the device up: its reads return 0 or fail (EIO), which tells a
    // lock-step device that the run is over (a line written now would be discarded with it).
    if (!link_path_.empty() && points_to(link_path_, path_, false)) ::unlink(link_path_.c_str());
    if (device_ >= 0) ::close(device_);
    if (master_ >= 0) ::close(master_);
  }

  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    // A misspelt mode or wait would leave the link in real time, its run not reproducible.
    ctx.refuse_unread_attributes();
    served_.configure(ctx);
    lockstep_ = p.choice("mode", {"realtime", "lockstep"}, "realtime") == "lockstep";
    // Each mode's own bound: the other one's would change nothing, so it is refused.
    const char* other = lockstep_ ? "timeout_s" : "wait_s";
    if (p.has(other))
      throw Error(ErrorKind::scene, p.where(other),
                  std::string(other) + " applies in mode='" +
                      (lockstep_ ? "realtime" : "lockstep") + "' only (this link is mode='" +
                      (lockstep_ ? "lockstep" : "realtime") + "'); remove it");
    if (lockstep_)
      wait_s_ = applied_wait_s(p.number("wait_s", 10.0, Range{0.0, kMaxWait_s, true}));
    else
      timeout_s_ = p.number("timeout_s", 0.5, Range{0.0, kMaxWait_s, true});
    if (p.has("period_s"))
      ctx.set_schedule(Stage::control, p.number("period_s", Range::positive()));

    master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0)
      throw Error(ErrorKind::plugin, p.where("kind"),
                  std::string("cannot open a pseudo-terminal: ") + std::strerror(errno));
    // Never block the simulation on a line nobody reads (posix_openpt may ignore O_NONBLOCK).
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    path_ = ::ptsname(master_);
    // Our own end of the device stays open: the master then never reads a hang-up, and the
    // line is raw (no echo of our writes, no line editing) whoever opens it later.
    device_ = ::open(path_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    termios raw{};
    if (device_ < 0 || ::tcgetattr(device_, &raw) != 0)
      throw Error(ErrorKind::plugin, p.where("kind"),
                  "cannot open " + path_ + ": " + std::strerror(errno));
    ::cfmakeraw(&raw);
    ::tcsetattr(device_, TCSANOW, &raw);
    if (p.has("link")) {  // a fixed name for the device, as socat's link=
      const std::string link = p.text("link");
      // Only a link to a pseudo-terminal (one a previous run left) is replaced: nothing else
      // that is there is ours to delete.
      struct stat there {};
      if (::lstat(link.c_str(), &there) == 0) {
        if (!S_ISLNK(there.st_mode) || !points_to(link, "/dev/pts/", true))
          throw Error(ErrorKind::scene, p.where("link"),
                      "'" + link +
                          "' exists and is not a link to a pseudo-terminal: it is left as it is; "
                          "choose another path or remove it");
        ::unlink(link.c_str());
      }
      link_path_ = link;
      if (::symlink(path_.c_str(), link_path_.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        link_path_.clear();
        throw Error(ErrorKind::scene, p.where("link"), "cannot create the link: " + why);
      }
    }
    pty_ = ctx.declare_signal("pty", "1");
    received_ = ctx.declare_signal("received", "1");
    dropped_ = ctx.declare_signal("dropped", "1");
    link_ = ctx.declare_signal("link", "1");
    timeouts_ = ctx.declare_signal("timeouts", "1");

    line_.assign(kMaxLine + 1, '\0');
    pending_.assign(4096, '\0');
    out_.assign(32 + 26 * (1 + served_.signals.size()), '\0');
    values_.assign(served_.inputs.size(), 0.0);
    description_ = "# s2sim-serial 1\n";
    for (const auto& in : served_.inputs)
      description_ += "# input " + in.name + " " + in.unit + "\n";
    for (const auto& s : served_.signals)
      description_ += "# signal " + s.name + " " + s.unit + "\n";
    description_ += "# end\n";
    if (p.boolean("announce", true))
      std::fprintf(stderr, "s2sim serial: %s serves %zu inputs and %zu signals on %s%s%s (%s)\n",
                   std::string(ctx.signal_prefix()).c_str(), served_.inputs.size(),
                   served_.signals.size(), path_.c_str(), link_path_.empty() ? "" : " = ",
                   link_path_.c_str(), lockstep_ ? "lock-step" : "real-time");
  }

  void initialize(StepContext& ctx) override {
    // /dev/pts/<n>: the number is the published part of the path.
    ctx.publish(pty_, std::strtod(path_.c_str() + path_.rfind('/') + 1, nullptr));
    detached_ = false;  // a reset run waits for its device again
  }

  void update(StepContext& ctx) override {
    if (lockstep_) {
      update_lockstep(ctx);
      return;
    }
    const Clock::time_point now = Clock::now();
    int reads = 0;
    do
      take_pending(ctx, now, false);
    while (reads++ < kMaxReadsPerPeriod && read_more());
    if (inputs_seen_ && seconds_between(last_inputs_, now) > timeout_s_) {
      lose_link(ctx);
      inputs_seen_ = false;
    }
    write_signals(ctx);
  }

 private:
  enum class Line { partial, inputs, query, dropped };

  void update_lockstep(StepContext& ctx) {
    // A detached link (its device did not answer) writes nothing until the device speaks.
    bool wrote = !detached_;
    if (wrote) write_signals(ctx);
    Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                    std::chrono::duration<double>(wait_s_));
    for (int reads = 0;;) {
      const Clock::time_point now = Clock::now();
      const Line got = take_pending(ctx, now, true);
      if (got == Line::inputs) {
        detached_ = false;
        return;  // this tick goes on with them
      }
      if (got == Line::query && detached_) {  // a device (again): this period waits for it
        detached_ = false;
        deadline = now + std::chrono::duration_cast<Clock::duration>(
                             std::chrono::duration<double>(wait_s_));
        if (!wrote) write_signals(ctx);
        wrote = true;
      }
      // Nobody answered in time (a flood of other lines included): a stopped robot, and no
      // more waiting.
      if (!detached_ && now >= deadline) {
        lose_link(ctx);
        detached_ = true;
        return;
      }
      if (got != Line::partial) continue;  // more bytes pending
      if ((!detached_ || reads++ < kMaxReadsPerPeriod) && read_more()) continue;
      if (detached_) return;
      pollfd device{master_, POLLIN, 0};
      const double left = seconds_between(now, deadline);
      ::poll(&device, 1, static_cast<int>(std::ceil(left * 1000.0)));  // EINTR: loop again
    }
  }

  /// Reads what the device sent into the pending bytes, once those are all taken.
  bool read_more() {
    if (begin_ < end_) return true;
    begin_ = end_ = 0;
    const ssize_t got = ::read(master_, pending_.data(), pending_.size());
    if (got <= 0) return false;
    end_ = static_cast<std::size_t>(got);
    return true;
  }

  /// Takes the pending bytes, up to the end of the first input line applied when `stop_at_inputs`
  /// (lock-step: the next line is the next tick's) or of the first `?` line. Returns what the
  /// last complete line was, or `partial` when every pending byte is taken.
  Line take_pending(StepContext& ctx, Clock::time_point now, bool stop_at_inputs) {
    while (begin_ < end_) {
      const Line got = take(ctx, pending_[begin_++], now);
      if (stop_at_inputs && (got == Line::inputs || got == Line::query)) return got;
    }
    return Line::partial;
  }

  Line take(StepContext& ctx, char c, Clock::time_point now) {
    // A line ends at LF, CR LF or CR: the LF of a CR LF ends no second, empty line.
    const bool after_cr = after_cr_;
    after_cr_ = c == '\r';
    if (c == '\n' && after_cr) return Line::partial;
    if (c != '\n' && c != '\r') {
      // A NUL or another control byte (a tab is a blank) makes the line garbage: "I 0.3<NUL>x"
      // must not be read as "I 0.3".
      const auto byte = static_cast<unsigned char>(c);
      if ((byte < 0x20 && c != '\t') || byte == 0x7f) control_ = true;
      if (length_ < kMaxLine) line_[length_] = c;
      ++length_;  // past kMaxLine: the line is too long, dropped at its end
      return Line::partial;
    }
    const Line got = length_ > kMaxLine || control_ ? Line::dropped : parse(ctx, now);
    if (got == Line::dropped) count(ctx, dropped_);
    length_ = 0;
    control_ = false;
    return got;
  }

  /// Whether `link` is a symbolic link to `target` (or, `prefix`, to a path starting with it).
  static bool points_to(const std::string& link, const std::string& target, bool prefix) {
    char buffer[4096];
    const ssize_t n = ::readlink(link.c_str(), buffer, sizeof buffer - 1);
    if (n < 0) return false;
    buffer[n] = '\0';
    return prefix ? std::strncmp(buffer, target.c_str(), target.size()) == 0 : buffer == target;
  }

  Line parse(StepContext& ctx, Clock::time_point now) {
    line_[length_] = '\0';
    const char* s = line_.data();
    if (length_ == 0) return Line::dropped;
    if (length_ == 1 && s[0] == '?') {
      write_all(description_.data(), description_.size());
      count(ctx, received_);
      return Line::query;
    }
    if (s[0] != 'I' || (length_ > 1 && s[1] != ' ')) return Line::dropped;
    const char* at = s + 1;
    for (double& v : values_) {
      char* end = nullptr;
      v = std::strtod(at, &end);
      if (end == at || !std::isfinite(v)) return Line::dropped;
      at = end;
    }
    while (*at == ' ' || *at == '\t')
      ++at;
    if (*at != '\0') return Line::dropped;  // more numbers than inputs, or garbage
    for (std::size_t i = 0; i < values_.size(); ++i)
      if (!ctx.input_accepts(served_.input_handles[i], values_[i])) return Line::dropped;
    for (std::size_t i = 0; i < values_.size(); ++i)
      ctx.set_input(served_.input_handles[i], values_[i]);
    inputs_seen_ = true;
    last_inputs_ = now;
    ctx.publish(link_, 1.0);
    count(ctx, received_);
    return Line::inputs;
  }

  void lose_link(StepContext& ctx) {
    for (const InputHandle in : served_.input_handles)
      ctx.set_input(in, 0.0);
    ctx.publish(link_, 0.0);
    count(ctx, timeouts_);
  }

  void write_signals(StepContext& ctx) {
    int n = std::snprintf(out_.data(), out_.size(), "S %.17g", ctx.time_s());
    for (const SignalReader& r : served_.readers)
      n += std::snprintf(out_.data() + n, out_.size() - static_cast<std::size_t>(n), " %.17g",
                         ctx.signal(r));
    out_[static_cast<std::size_t>(n)] = '\n';
    write_all(out_.data(), static_cast<std::size_t>(n) + 1);
  }

  void write_all(const char* data, std::size_t size) {
    // Best effort: nobody reading and the terminal's buffer full means the line is lost, as
    // on a real serial line.
    (void)::write(master_, data, size);
  }
  static void count(StepContext& ctx, SignalHandle h) { ctx.publish(h, ctx.signal(h) + 1.0); }

  ServedSet served_;
  bool lockstep_ = false;
  double timeout_s_ = 0.5, wait_s_ = 10.0;
  int master_ = -1, device_ = -1;
  std::string path_, link_path_, description_;
  SignalHandle pty_, received_, dropped_, link_, timeouts_;
  std::vector<char> line_, out_;
  std::vector<char> pending_;        // bytes read from the device, not yet taken
  std::size_t begin_ = 0, end_ = 0;  // of those in pending_
  std::vector<double> values_;
  std::size_t length_ = 0;
  bool inputs_seen_ = false, after_cr_ = false;
  bool control_ = false;   // the line being read holds a control byte
  bool detached_ = false;  // lock-step: the device did not answer; run on without waiting
  Clock::time_point last_inputs_{};
};

}  // namespace

s2sim_kind_entry serial_kind() {
  return S2SIM_KIND("serial", Category::controller, Serial);
}

}  // namespace s2sim::links
