// The plugin's one exported symbol: the descriptor naming its kinds (S2SIM_PLUGIN).
#include "kinds.hpp"

S2SIM_PLUGIN("example_rover", S2SIM_KIND("compass", s2sim::Category::sensor, rover::Compass),
             S2SIM_KIND("speed_servo", s2sim::Category::actuator, rover::SpeedServo),
             S2SIM_KIND("heading_controller", s2sim::Category::controller,
                        rover::HeadingController));
