// The `remote` controller: serves a robot's (or the scene's) inputs and signals over UDP in
// the S2Sim remote protocol (include/s2sim_remote.h, docs/remote.md). Real-time mode never
// waits: every control period it reads what has arrived and sends the signals, as SimTwo does.
// Lock-step mode advances one control period per INPUTS request, so a slow client still gets a
// deterministic run.
//
// The link's own bookkeeping (client address, sequence numbers, wall-clock times) lives in
// members, not in declared state: it describes the connection, not the simulated world, and
// restoring a snapshot must not roll a client's sequence numbers back. The counters are
// published signals (kernel memory).
#define S2SIM_REMOTE_NO_CLIENT
#include "datagram_key.hpp"
#include "include/s2sim_remote.h"
#include "kinds.hpp"
#include "link_waits.hpp"
#include "served_set.hpp"
#include "udp_socket.hpp"

#include <s2sim/sdk.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace s2sim::links {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

class Remote final : public Component {
 public:
  // The simulation is destroyed: its run is over (the runner's --duration, a closed viewer,
  // an error). A lock-step client would otherwise wait for its next reply until its own
  // timeout, so the client of an open session is told.
  ~Remote() override {
    if (has_client_ && !end_.empty()) {
      s2sim_remote_write_header(end_.data(), S2SIM_REMOTE_END, last_sequence_, payload_size(end_));
      s2sim_remote_put_f64(end_.data() + 16, last_time_s_);
      send(end_, client_);
    }
  }

  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    served_.configure(ctx);  // before our own signals, which are not served
    lockstep_ = p.choice("mode", {"realtime", "lockstep"}, "realtime") == "lockstep";
    timeout_s_ = p.number("timeout_s", 0.5, Range{0.0, kMaxWait_s, true});
    wait_s_ = applied_wait_s(p.number("wait_s", 10.0, Range{0.0, kMaxWait_s, true}));
    const std::string address = p.text("address", "127.0.0.1");
    const bool allow_remote = p.boolean("allow_remote", false);
    if (p.has("key_file")) key_.load(p.text("key_file"), p.where("key_file"));
    if (allow_remote && !key_.present())
      throw Error(ErrorKind::scene, p.where("allow_remote"),
                  "allow_remote='1' needs key_file='...' (a shared key of at least " +
                      std::to_string(DatagramKey::kMinKeyBytes) +
                      " bytes): without one, anyone on the network could drive the robot");
    socket_.bind(address, p.integer_in("port", S2SIM_REMOTE_DEFAULT_PORT, 0, 65535), allow_remote,
                 p.where("address"));
    if (p.has("period_s")) {
      const double period = p.number("period_s", Range::positive());
      ctx.set_schedule(Stage::control, period);
    }

    port_ = ctx.declare_signal("port", "1");
    received_ = ctx.declare_signal("received", "1");
    dropped_ = ctx.declare_signal("dropped", "1");
    stale_ = ctx.declare_signal("stale", "1");
    foreign_ = ctx.declare_signal("foreign", "1");
    unauthenticated_ = ctx.declare_signal("unauthenticated", "1");
    link_ = ctx.declare_signal("link", "1");
    timeouts_ = ctx.declare_signal("timeouts", "1");

    // Everything sent is laid out now: update() only fills numbers in. The description's
    // period is known once the schedule is (initialize()).
    rx_.assign(S2SIM_REMOTE_MAX_DATAGRAM + 1, 0);
    const std::string busy =
        "busy: this link serves another client; try again after it is "
        "silent for " +
        std::to_string(lockstep_ ? wait_s_ : timeout_s_) + " s";
    const std::size_t tag = key_.tag_size();
    busy_.assign(S2SIM_REMOTE_HEADER_SIZE + busy.size() + tag, 0);
    std::copy(busy.begin(), busy.end(), busy_.begin() + S2SIM_REMOTE_HEADER_SIZE);
    signals_packet_.assign(S2SIM_REMOTE_HEADER_SIZE + 8 * (1 + served_.signals.size()) + tag, 0);
    const std::string end = "end: the simulation ended; no more replies will come";
    end_.assign(S2SIM_REMOTE_HEADER_SIZE + 8 + end.size() + tag, 0);
    std::copy(end.begin(), end.end(), end_.begin() + S2SIM_REMOTE_HEADER_SIZE + 8);
    build_description(-0.12345678901234567);  // the size check, with a period as long as any
    const std::size_t largest =
        std::max({describe_.size(), signals_packet_.size(),
                  S2SIM_REMOTE_HEADER_SIZE + 8 * served_.inputs.size() + tag});
    if (largest > S2SIM_REMOTE_MAX_DATAGRAM)
      throw Error(ErrorKind::scene, p.where("signals"),
                  "the served inputs and signals do not fit in one datagram (" +
                      std::to_string(largest) + " bytes > " +
                      std::to_string(S2SIM_REMOTE_MAX_DATAGRAM) +
                      "): narrow them with inputs='...' and signals='...' patterns");
    if (p.boolean("announce", true))
      std::fprintf(stderr,
                   "s2sim remote: %s serves %zu inputs and %zu signals on udp %s:%d (%s%s)\n",
                   std::string(ctx.signal_prefix()).c_str(), served_.inputs.size(),
                   served_.signals.size(), address.c_str(), socket_.port(),
                   lockstep_ ? "lock-step" : "real-time", key_.present() ? ", keyed" : "");
  }

  // At load and at reset, outside the step loop: the one place the description is rebuilt.
  void initialize(StepContext& ctx) override {
    ctx.publish(port_, socket_.port());
    has_client_ = false;  // a reset run starts without a session: the next sender opens one
    last_time_s_ = ctx.time_s();
    build_description(ctx.period_s());
  }

  void update(StepContext& ctx) override {
    last_time_s_ = ctx.time_s();
    if (lockstep_)
      update_lockstep(ctx);
    else
      update_realtime(ctx);
  }

 private:
  void build_description(double period_s) {
    char period[64];
    std::snprintf(period, sizeof period, "%.17g", period_s);
    std::string text = "s2sim-remote 1\nmode " + std::string(lockstep_ ? "lockstep" : "realtime") +
                       "\nperiod " + period + "\n";
    for (const auto& in : served_.inputs)
      text += "input " + in.name + " " + in.unit + "\n";
    for (const auto& s : served_.signals)
      text += "signal " + s.name + " " + s.unit + "\n";
    describe_.assign(S2SIM_REMOTE_HEADER_SIZE + text.size() + key_.tag_size(), 0);
    std::copy(text.begin(), text.end(), describe_.begin() + S2SIM_REMOTE_HEADER_SIZE);
  }

  enum class Got { nothing, dropped, hello, observe, inputs, repeat, bye };
  // A flood must not hold the simulation: at most this many datagrams are read per period
  // (the rest waits in the socket, or is dropped by the system when it fills).
  static constexpr int kMaxDatagramsPerPeriod = 20000;

  void update_realtime(StepContext& ctx) {
    const Clock::time_point now = Clock::now();
    for (int n = 0; n < kMaxDatagramsPerPeriod; ++n) {
      sockaddr_in from{};
      const long size = socket_.receive(rx_.data(), rx_.size(), 0.0, &from);
      if (size < 0) break;
      handle(ctx, size, from, now);
    }
    if (inputs_seen_ && seconds_between(last_inputs_, now) > timeout_s_) lose_link(ctx);
    if (has_client_) send_signals(ctx, ++sent_sequence_);
  }

  void update_lockstep(StepContext& ctx) {
    if (has_client_ && !detached_) send_signals(ctx, reply_sequence_);  // the last step's reply
    Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                    std::chrono::duration<double>(wait_s_));
    for (int n = 0; n < kMaxDatagramsPerPeriod || !detached_; ++n) {
      const Clock::time_point now = Clock::now();
      const double wait = detached_ ? 0.0 : seconds_between(now, deadline);
      sockaddr_in from{};
      const long size =
          wait > 0 || detached_ ? socket_.receive(rx_.data(), rx_.size(), wait, &from) : -1;
      if (size < 0) {
        if (!detached_) {  // nobody asked in time: a stopped robot, and no more waiting
          lose_link(ctx);
          detached_ = true;
        }
        return;
      }
      const bool was_detached = detached_;
      const Got got = handle(ctx, size, from, now);
      if (got == Got::hello) {
        detached_ = false;  // a client (again): wait for its requests from now on
        if (was_detached)
          deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(wait_s_));
      }
      if (got == Got::inputs) {
        detached_ = false;
        return;  // advance one period
      }
    }
  }

  /// Whether `from` may speak at `now`: the session's own client, or anyone while no session is
  /// open (none yet, or its client silent for longer than the link waits for it: timeout_s in
  /// real time, wait_s in lock-step).
  bool may_speak(const sockaddr_in& from, Clock::time_point now) const {
    const bool open = has_client_ && !detached_ &&
                      seconds_between(last_heard_, now) <= (lockstep_ ? wait_s_ : timeout_s_);
    return !open || same_sender(from, client_);
  }
  static bool same_sender(const sockaddr_in& a, const sockaddr_in& b) {
    return a.sin_addr.s_addr == b.sin_addr.s_addr && a.sin_port == b.sin_port;
  }

  Got handle(StepContext& ctx, long size, const sockaddr_in& from, Clock::time_point now) {
    s2sim_remote_header h{};
    if (static_cast<std::size_t>(size) >= rx_.size()) return drop(ctx);  // oversized (cut)
    if (key_.present()) {  // before anything else: an unsigned datagram is nobody's
      if (!key_.verify(rx_.data(), static_cast<std::size_t>(size))) {
        count(ctx, unauthenticated_);
        return drop(ctx);
      }
      size -= static_cast<long>(DatagramKey::kTagSize);
    }
    if (s2sim_remote_read_header(rx_.data(), static_cast<std::size_t>(size), &h) != 0)
      return drop(ctx);
    const bool request = h.type == S2SIM_REMOTE_HELLO || h.type == S2SIM_REMOTE_INPUTS ||
                         h.type == S2SIM_REMOTE_OBSERVE || h.type == S2SIM_REMOTE_BYE;
    if (request && !may_speak(from, now)) {
      // Another sender while a client holds the session: told so, counted, never applied.
      s2sim_remote_write_header(busy_.data(), S2SIM_REMOTE_BUSY, h.sequence, payload_size(busy_));
      send(busy_, from);
      count(ctx, foreign_);
      return drop(ctx);
    }
    if (request && has_client_ && !same_sender(from, client_))
      has_client_ = false;  // a new session: its sequence numbers start afresh
    if (request) last_heard_ = now;
    switch (h.type) {
      case S2SIM_REMOTE_HELLO:
        if (h.length != 0) return drop(ctx);
        client_ = from;
        has_client_ = true;
        last_sequence_ = h.sequence;
        s2sim_remote_write_header(describe_.data(), S2SIM_REMOTE_DESCRIBE, h.sequence,
                                  payload_size(describe_));
        send(describe_, from);
        count(ctx, received_);
        return Got::hello;
      case S2SIM_REMOTE_BYE:  // the client leaves: the session is free (the inputs stay)
        if (h.length != 0) return drop(ctx);
        has_client_ = false;
        count(ctx, received_);
        return Got::bye;
      case S2SIM_REMOTE_OBSERVE:
        if (h.length != 0) return drop(ctx);
        fill_signals(ctx, h.sequence);
        send(signals_packet_, from);
        count(ctx, received_);
        return Got::observe;
      case S2SIM_REMOTE_INPUTS: {
        if (h.length != 8 * served_.inputs.size()) return drop(ctx);
        for (std::size_t i = 0; i < served_.inputs.size(); ++i)  // NaN is outside every range
          if (!ctx.input_accepts(served_.input_handles[i],
                                 s2sim_remote_get_f64(rx_.data() + 16 + 8 * i)))
            return drop(ctx);
        if (has_client_ && h.sequence <= last_sequence_) {
          if (lockstep_ && h.sequence == last_sequence_ && h.sequence == reply_sequence_) {
            // The client did not get our reply and asks again: answer, do not advance twice.
            send(signals_packet_, from);
            return Got::repeat;
          }
          count(ctx, stale_);
          return drop(ctx);
        }
        for (std::size_t i = 0; i < served_.inputs.size(); ++i)
          ctx.set_input(served_.input_handles[i], s2sim_remote_get_f64(rx_.data() + 16 + 8 * i));
        client_ = from;
        has_client_ = true;
        last_sequence_ = reply_sequence_ = h.sequence;
        inputs_seen_ = true;
        last_inputs_ = now;
        ctx.publish(link_, 1.0);
        count(ctx, received_);
        return Got::inputs;
      }
      default:
        return drop(ctx);
    }
  }

  void lose_link(StepContext& ctx) {
    for (const InputHandle in : served_.input_handles)
      ctx.set_input(in, 0.0);
    if (ctx.signal(link_) != 0.0) count(ctx, timeouts_);
    ctx.publish(link_, 0.0);
    inputs_seen_ = false;  // zeroed once; a new INPUTS restarts the clock
  }

  void fill_signals(StepContext& ctx, std::uint32_t sequence) {
    unsigned char* out = signals_packet_.data();
    s2sim_remote_write_header(out, S2SIM_REMOTE_SIGNALS, sequence, payload_size(signals_packet_));
    s2sim_remote_put_f64(out + 16, ctx.time_s());
    for (std::size_t i = 0; i < served_.readers.size(); ++i)
      s2sim_remote_put_f64(out + 24 + 8 * i, ctx.signal(served_.readers[i]));
  }
  void send_signals(StepContext& ctx, std::uint32_t sequence) {
    fill_signals(ctx, sequence);
    send(signals_packet_, client_);
  }

  /// A packet's payload bytes: all but its header and its tag.
  std::uint32_t payload_size(const std::vector<unsigned char>& packet) const {
    return static_cast<std::uint32_t>(packet.size() - S2SIM_REMOTE_HEADER_SIZE - key_.tag_size());
  }
  /// Sends a packet laid out with room for its tag, signed first when the link has a key.
  void send(std::vector<unsigned char>& packet, const sockaddr_in& to) {
    if (key_.present()) key_.seal(packet.data(), packet.size() - DatagramKey::kTagSize);
    socket_.send(packet.data(), packet.size(), to);
  }

  Got drop(StepContext& ctx) {
    count(ctx, dropped_);
    return Got::dropped;
  }
  static void count(StepContext& ctx, SignalHandle h) { ctx.publish(h, ctx.signal(h) + 1.0); }

  ServedSet served_;
  UdpSocket socket_;
  bool lockstep_ = false;
  double timeout_s_ = 0.5, wait_s_ = 10.0;
  SignalHandle port_, received_, dropped_, stale_, foreign_, unauthenticated_, link_, timeouts_;
  DatagramKey key_;
  std::vector<unsigned char> rx_, signals_packet_, describe_;

  // The connection (see the file comment).
  sockaddr_in client_{};
  bool has_client_ = false;
  bool detached_ = false;  // lock-step: the client went silent; run on without waiting
  bool inputs_seen_ = false;
  std::uint32_t last_sequence_ = 0, reply_sequence_ = 0, sent_sequence_ = 0;
  Clock::time_point last_inputs_{};
  Clock::time_point last_heard_{};   // the client's last valid-looking request
  std::vector<unsigned char> busy_;  // the BUSY reply to another sender
  std::vector<unsigned char> end_;   // END, sent to the client when the simulation ends
  double last_time_s_ = 0;           // of the last control period, for END
};

}  // namespace

s2sim_kind_entry remote_kind() {
  return S2SIM_KIND("remote", Category::controller, Remote);
}

}  // namespace s2sim::links
