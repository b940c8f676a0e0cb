// The well-behaved test plugin: a real component and a factory that fails.
// S2SIM_TEST_PLUGIN_NAME and S2SIM_TEST_COUNTER_KIND let CMake build the same source as other
// valid plugins (a duplicate of `test_counter`, the good half of the `mixed` folder).

#include <s2sim/plugin.hpp>

#include <atomic>
#include <stdexcept>

#ifndef S2SIM_TEST_PLUGIN_NAME
#define S2SIM_TEST_PLUGIN_NAME "test_good"
#endif
#ifndef S2SIM_TEST_COUNTER_KIND
#define S2SIM_TEST_COUNTER_KIND "test_counter"
#endif

namespace {

// Live instances, so a test can check that the kernel destroys what it created.
std::atomic<int> live_components{0};

// Counts its updates in a state slot and publishes the count.
class TestCounter : public s2sim::Component {
 public:
  TestCounter() { ++live_components; }
  ~TestCounter() override { --live_components; }

  void configure(s2sim::ConfigureContext& ctx) override {
    count_ = ctx.declare_state("count", 1, 0.0);
    signal_ = ctx.declare_signal("count", "1");
  }
  void initialize(s2sim::StepContext& ctx) override { ctx.state(count_)[0] = 0.0; }
  void update(s2sim::StepContext& ctx) override {
    const s2sim::Span<double> count = ctx.state(count_);
    count[0] += 1.0;
    ctx.publish(signal_, count[0]);
  }

 private:
  s2sim::StateHandle count_;
  s2sim::SignalHandle signal_;
};

class TestThrowingFactory : public s2sim::Component {
 public:
  TestThrowingFactory() { throw std::runtime_error("thruster needs a propeller"); }
  void configure(s2sim::ConfigureContext&) override {}
  void update(s2sim::StepContext&) override {}
};

}  // namespace

// Test hook, looked up with dlsym by the loader test; not part of the plugin ABI.
extern "C" S2SIM_EXPORT int s2sim_test_live_components(void) {
  return live_components.load();
}

#ifdef S2SIM_TEST_COUNTER_ONLY
S2SIM_PLUGIN(S2SIM_TEST_PLUGIN_NAME,
             S2SIM_KIND(S2SIM_TEST_COUNTER_KIND, s2sim::Category::sensor, TestCounter))
#else
S2SIM_PLUGIN(S2SIM_TEST_PLUGIN_NAME,
             S2SIM_KIND(S2SIM_TEST_COUNTER_KIND, s2sim::Category::sensor, TestCounter),
             S2SIM_KIND("test_throwing_factory", s2sim::Category::actuator, TestThrowingFactory))
#endif
