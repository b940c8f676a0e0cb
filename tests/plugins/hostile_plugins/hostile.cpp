// A plugin that misbehaves on purpose (../shared/repro R07, R08): it throws from
// configure() or update(), an s2sim::Error (whose type info and vtable live in this library),
// a std::exception or something that is not an exception at all, or crashes (SIGSEGV; an
// endless recursion; a trap on a thread of its own), or hangs in its update, or is slow. Built like
// a third party's. Its constructor crashes when the environment variable
// S2SIM_TEST_HOSTILE_CRASH_IN_CONSTRUCTOR is set (a factory has no parameters), its destructor
// in mode 'destroy_segv'.
#include <s2sim/sdk.hpp>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

namespace {

using namespace s2sim;

/// Recurses until the stack runs out (the depth is never reached; `pad` keeps every frame).
__attribute__((noinline)) int recurse(int depth, int never) {
  volatile char pad[512];
  pad[0] = static_cast<char>(depth);
  if (depth == never) return pad[0];
  return recurse(depth + 1, never) + pad[0];
}

class Hostile : public Component {
 public:
  Hostile() {
    if (std::getenv("S2SIM_TEST_HOSTILE_CRASH_IN_CONSTRUCTOR") != nullptr) std::raise(SIGSEGV);
  }
  ~Hostile() override {
    if (mode_ == "destroy_segv") std::raise(SIGSEGV);
    if (thread_.joinable()) thread_.join();
  }
  void configure(ConfigureContext& ctx) override {
    mode_ = ctx.params().text("mode");
    if (mode_ == "configure_error")
      throw Error(ErrorKind::scene, "hostile: the parameter 'mode' is not to my liking");
    if (mode_ == "configure_std") throw std::runtime_error("hostile: a std::runtime_error");
    if (mode_ == "configure_int") throw 42;
    if (mode_ == "nan_force") body_ = ctx.body(ctx.params().text("solid"));
  }
  void update(StepContext& ctx) override {
    if (ctx.tick() < 3) return;
    if (mode_ == "update_error") throw Error(ErrorKind::runtime, "hostile: failed in update");
    if (mode_ == "update_std") throw std::runtime_error("hostile: a std::runtime_error in update");
    if (mode_ == "update_int") throw 7;
    if (mode_ == "nan_force") ctx.apply_torque(body_, Vec3{0, 0, std::nan("")});
    // Handles never looked up: the accessors refuse them rather than read out of bounds.
    if (mode_ == "unset_body") ctx.apply_force(body_, Vec3{1, 0, 0}, Vec3{});
    if (mode_ == "unset_axis") ctx.apply_axis_force(AxisHandle{}, 1.0);
    if (mode_ == "unset_input") ctx.set_input(InputHandle{}, 1.0);
    if (mode_ == "unset_state") ctx.state(StateHandle{})[0] = 1.0;
    if (mode_ == "far_body") ctx.body_pose(BodyHandle{1 << 30});
    if (mode_ == "update_segv") std::raise(SIGSEGV);  // a crash, without undefined behaviour
    if (mode_ == "update_recurse") recurse(0, -1);
    if (mode_ == "update_hang")  // never returns (a `while true do;` in a script)
      for (;;)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (mode_ == "update_slow") std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (mode_ == "update_exit0") std::exit(0);  // as a careless plugin ends "its" program
    if (mode_ == "update_exit3") std::exit(3);
    if (mode_ == "update__exit0") ::_exit(0);  // no atexit handler sees this one
    if (mode_ == "update__Exit3") std::_Exit(3);
    // A crash on a thread of the plugin's own, outside any call of the kernel into it.
    if (mode_ == "thread_trap" && !thread_.joinable())
      thread_ = std::thread([] { __builtin_trap(); });
  }

 private:
  std::string mode_;
  BodyHandle body_;
  std::thread thread_;
};

}  // namespace

S2SIM_PLUGIN("s2sim_test_hostile", S2SIM_KIND("test_hostile", Category::controller, Hostile))
