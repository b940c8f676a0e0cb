#pragma once
/// \file
/// Compiling and linking GLSL programs (the world view's shaders).

namespace s2sim::render {

/// Compiles and links a vertex and a fragment shader, with `defines` ("#define X\n" lines)
/// inserted after the fragment shader's #version line. Throws std::runtime_error with the
/// driver's log when either fails.
unsigned link_program(const char* vertex_source, const char* fragment_source,
                      const char* defines = "");

/// The location of a uniform (-1 when the program has none of that name).
int uniform(unsigned program, const char* name);

}  // namespace s2sim::render
