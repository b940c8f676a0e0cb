#pragma once
/// \file
/// The viewer application: a GLFW window with an OpenGL 3.3 core context, Dear ImGui on top,
/// and the main loop (input, run control, world view, windows, screenshots).

#include "options.hpp"

namespace s2sim::viewer {

/// Runs the viewer until its window closes (or --frames / the script ends). Returns the
/// process exit code. Throws s2sim::Error for a bad scene or option.
int run_viewer(const Options& options);

}  // namespace s2sim::viewer
