#include "gl_program.hpp"

#include "gl.hpp"

#include <stdexcept>
#include <string>

namespace s2sim::render {
namespace {

unsigned compile(GLenum type, const char* source) {
  const unsigned shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("shader compilation failed: ") + log);
  }
  return shader;
}

}  // namespace

unsigned link_program(const char* vertex_source, const char* fragment_source, const char* defines) {
  std::string fragment = fragment_source;
  fragment.insert(fragment.find('\n') + 1, defines);
  const unsigned vs = compile(GL_VERTEX_SHADER, vertex_source);
  const unsigned fs = compile(GL_FRAGMENT_SHADER, fragment.c_str());
  const unsigned program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw std::runtime_error(std::string("shader link failed: ") + log);
  }
  return program;
}

int uniform(unsigned program, const char* name) {
  return glGetUniformLocation(program, name);
}

}  // namespace s2sim::render
