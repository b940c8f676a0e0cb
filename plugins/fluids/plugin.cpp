/// \file
/// The fluids plugin: drag, buoyancy and propeller actuators (docs/models/fluids.md). The
/// kernel also makes them for SimTwo's `<drag>`, `<buoyant>` and `<propeller>` solids
/// (kernel/src/sim/fluid_components.hpp).

#include "buoyancy.hpp"
#include "drag.hpp"
#include "propeller.hpp"

#include <s2sim/plugin.hpp>

S2SIM_PLUGIN("fluids", S2SIM_KIND("drag", s2sim::Category::actuator, s2sim::fluids::Drag),
             S2SIM_KIND("buoyancy", s2sim::Category::actuator, s2sim::fluids::Buoyancy),
             S2SIM_KIND("propeller", s2sim::Category::actuator, s2sim::fluids::Propeller));
