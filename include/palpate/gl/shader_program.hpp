#pragma once
// A linked GLSL program. Compile and link errors throw palpate::Error with the driver's log and the
// program's name. Needs a current OpenGL 4.5 context.
#include <epoxy/gl.h>

#include <string>
#include <string_view>

namespace palpate::gl {

class ShaderProgram {
 public:
  ShaderProgram() = default;
  ShaderProgram(std::string name, std::string_view vertex_source, std::string_view fragment_source);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  GLuint id() const noexcept { return program_; }
  const std::string& name() const noexcept { return name_; }
  // -1 where the program has no such active uniform.
  GLint uniform(const char* uniform_name) const noexcept {
    return glGetUniformLocation(program_, uniform_name);
  }

 private:
  std::string name_;
  GLuint program_ = 0;
};

}  // namespace palpate::gl
