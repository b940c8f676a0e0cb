#pragma once
/// \file
/// The runner's and the viewer's command lines load a scene the same way: their options
/// (`seed`, `physics_step_s`, `substeps`, `constants`, `plugin_path`, and `threads` and
/// `default_plugin_path` where the command line has them) become the façade's.

#include <s2sim/kernel/simulation.hpp>

namespace s2sim::apps {

template <class CommandLine>
SimulationOptions simulation_options(const CommandLine& o) {
  SimulationOptions so;
  so.seed = o.seed;
  so.physics_step_s = o.physics_step_s;
  so.substeps = o.substeps;
  so.constants = o.constants;
  if constexpr (requires { o.threads; }) so.threads = o.threads;
  if constexpr (requires { o.simbody_dynamics_only; })
    so.simbody_dynamics_only = o.simbody_dynamics_only;
  if constexpr (requires { o.check_dynamics; }) so.check_dynamics = o.check_dynamics;
  for (const auto& p : o.plugin_path)
    so.plugin_path.emplace_back(p);
  if constexpr (requires { o.model_path; })
    for (const auto& p : o.model_path)
      so.model_path.emplace_back(p);
  if constexpr (requires { o.default_plugin_path; }) so.default_plugin_path = o.default_plugin_path;
  if constexpr (requires { o.script_mode; }) {  // the runner's SimTwo script options
    so.script_mode = o.script_mode;
    if (!o.script_file.empty()) so.script_file = o.script_file;
  }
  return so;
}

}  // namespace s2sim::apps
