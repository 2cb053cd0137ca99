#include "palpate/gl/shader_program.hpp"

#include <epoxy/gl.h>

#include <utility>

#include "current_context.hpp"
#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  return log;
}

GLuint compile(const std::string& program_name, GLenum stage, std::string_view source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = shader_log(shader);
    glDeleteShader(shader);
    throw Error("shader program '" + program_name + "': " +
                (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") + " shader failed to compile:\n" + log);
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(std::string name, std::string_view vertex_source,
                             std::string_view fragment_source)
    : name_(std::move(name)) {
  const GLuint vertex = compile(name_, GL_VERTEX_SHADER, vertex_source);
  GLuint fragment = 0;
  try {
    fragment = compile(name_, GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program_, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
    glGetProgramInfoLog(program_, length, nullptr, log.data());
    glDeleteProgram(program_);
    program_ = 0;
    throw Error("shader program '" + name_ + "' failed to link:\n" + log);
  }
}

ShaderProgram::~ShaderProgram() {
  if (program_ && a_context_is_current()) glDeleteProgram(program_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : name_(std::move(other.name_)), program_(std::exchange(other.program_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (program_ && a_context_is_current()) glDeleteProgram(program_);
    name_ = std::move(other.name_);
    program_ = std::exchange(other.program_, 0);
  }
  return *this;
}

std::int32_t ShaderProgram::uniform(const char* uniform_name) const noexcept {
  return glGetUniformLocation(program_, uniform_name);
}

}  // namespace palpate::gl
