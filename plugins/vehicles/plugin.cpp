/// \file
/// The vehicles plugin: the pilots of scenes/quadrotor, scenes/boat and scenes/blimp, examples
/// of controller plugins flying the fluids plugin's propellers (docs/models/fluids.md).

#include "blimp_pilot.hpp"
#include "boat_pilot.hpp"
#include "quadrotor_pilot.hpp"

#include <s2sim/plugin.hpp>

S2SIM_PLUGIN("vehicles",
             S2SIM_KIND("quadrotor_pilot", s2sim::Category::controller,
                        s2sim::vehicles::QuadrotorPilot),
             S2SIM_KIND("boat_pilot", s2sim::Category::controller, s2sim::vehicles::BoatPilot),
             S2SIM_KIND("blimp_pilot", s2sim::Category::controller, s2sim::vehicles::BlimpPilot));
