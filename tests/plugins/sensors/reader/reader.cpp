// A controller that reads a sensor's reading through the SDK and republishes it, built like a
// third-party plugin.
#include <s2sim/sdk.hpp>

namespace {

using namespace s2sim;

class SensorReader : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    source_ = ctx.published_signal(ctx.params().text("signal"));
    seen_ = ctx.declare_signal("seen", "m");
    ctx.set_schedule(Stage::control, ctx.tick_s());
  }
  void update(StepContext& ctx) override { ctx.publish(seen_, ctx.signal(source_)); }

 private:
  SignalHandle source_, seen_;
};

}  // namespace

S2SIM_PLUGIN("s2sim_test_sensor_reader",
             S2SIM_KIND("test_sensor_reader", Category::controller, SensorReader))
