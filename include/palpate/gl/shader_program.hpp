#pragma once
// A linked GLSL program. Compile and link errors throw palpate::Error with the driver's log and the
// program's name. Needs a current OpenGL context (2.0 or later). GL names are plain integers here.
#include <cstdint>
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

  std::uint32_t id() const noexcept { return program_; }
  const std::string& name() const noexcept { return name_; }
  // -1 where the program has no such active uniform.
  std::int32_t uniform(const char* uniform_name) const noexcept;

 private:
  std::string name_;
  std::uint32_t program_ = 0;
};

}  // namespace palpate::gl
