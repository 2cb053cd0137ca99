#include "palpate/gl/deform_uniforms.hpp"

#include <epoxy/gl.h>

#include <string>
#include <utility>

#include "current_context.hpp"
#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

bool has_uniform_buffers() noexcept {
  return epoxy_gl_version() >= 31 || epoxy_has_gl_extension("GL_ARB_uniform_buffer_object");
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  return log.empty() ? "(no log)" : log;
}

void delete_buffer(GLuint buffer) noexcept {
  if (buffer && a_context_is_current()) glDeleteBuffers(1, &buffer);
}

}  // namespace

DeformUniforms::DeformUniforms(std::uint32_t program, std::uint32_t block_binding)
    : program_(program), binding_(block_binding) {
  GLint linked = GL_FALSE;
  if (!glIsProgram(program))
    throw Error("DeformUniforms: " + std::to_string(program) + " is not a shader program");
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) {
    throw Error("DeformUniforms: program " + std::to_string(program) +
                " did not link (fix its shaders first): " + program_log(program));
  }
  if (has_uniform_buffers()) {
    const GLuint index = glGetUniformBlockIndex(program, deform_block_name);
    if (index != GL_INVALID_INDEX) {
      dialect_ = GlslDialect::uniform_block;
      glUniformBlockBinding(program, index, binding_);
      GLint previous = 0;
      glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &previous);
      glGenBuffers(1, &buffer_);
      glBindBuffer(GL_UNIFORM_BUFFER, buffer_);
      glBufferData(GL_UNIFORM_BUFFER, sizeof(DeformBlockData), &data_, GL_DYNAMIC_DRAW);
      glBindBuffer(GL_UNIFORM_BUFFER, GLuint(previous));
      return;
    }
  }
  dialect_ = GlslDialect::uniform_arrays;
  center_depth_location_ = glGetUniformLocation(program, "palpate_dent_center_depth");
  shape_location_ = glGetUniformLocation(program, "palpate_dent_shape");
  count_location_ = glGetUniformLocation(program, "palpate_dent_count");
  surface_dent_location_ = glGetUniformLocation(program, "palpate_surface_dent");
  surface_normal_location_ = glGetUniformLocation(program, "palpate_surface_normal");
  if (center_depth_location_ < 0 && shape_location_ < 0) {
    throw Error("DeformUniforms: program " + std::to_string(program) + " has neither the uniform block " +
                deform_block_name +
                " nor the palpate_dent_* uniform arrays: build its shaders with insert_deform_glsl and call "
                "palpate_displace or palpate_perturb_normal in them");
  }
}

DeformUniforms::~DeformUniforms() {
  delete_buffer(buffer_);
}

DeformUniforms::DeformUniforms(DeformUniforms&& other) noexcept
    : program_(other.program_),
      dialect_(other.dialect_),
      buffer_(std::exchange(other.buffer_, 0)),
      binding_(other.binding_),
      center_depth_location_(other.center_depth_location_),
      shape_location_(other.shape_location_),
      count_location_(other.count_location_),
      surface_dent_location_(other.surface_dent_location_),
      surface_normal_location_(other.surface_normal_location_),
      data_(other.data_) {}

DeformUniforms& DeformUniforms::operator=(DeformUniforms&& other) noexcept {
  if (this != &other) {
    delete_buffer(buffer_);
    program_ = other.program_;
    dialect_ = other.dialect_;
    buffer_ = std::exchange(other.buffer_, 0);
    binding_ = other.binding_;
    center_depth_location_ = other.center_depth_location_;
    shape_location_ = other.shape_location_;
    count_location_ = other.count_location_;
    surface_dent_location_ = other.surface_dent_location_;
    surface_normal_location_ = other.surface_normal_location_;
    data_ = other.data_;
  }
  return *this;
}

int DeformUniforms::set(std::span<const Dent> dents) noexcept {
  data_ = make_deform_block_data(dents);
  if (buffer_) {
    GLint previous = 0;
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &previous);
    glBindBuffer(GL_UNIFORM_BUFFER, buffer_);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof(DeformBlockData), &data_);
    glBindBuffer(GL_UNIFORM_BUFFER, GLuint(previous));
  }
  return static_cast<int>(dents.size()) - data_.count;
}

void DeformUniforms::apply() const noexcept {
  if (buffer_) {
    GLint previous = 0;  // glBindBufferBase also sets the generic binding: leave that as found
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &previous);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding_, buffer_);
    glBindBuffer(GL_UNIFORM_BUFFER, GLuint(previous));
    return;
  }
  if (center_depth_location_ >= 0) glUniform4fv(center_depth_location_, max_dents, &data_.center_depth[0].x);
  if (shape_location_ >= 0) glUniform4fv(shape_location_, max_dents, &data_.shape[0].x);
  if (count_location_ >= 0) glUniform1i(count_location_, data_.count);
  if (surface_dent_location_ >= 0) glUniform1i(surface_dent_location_, data_.surface_dent);
  if (surface_normal_location_ >= 0) glUniform4fv(surface_normal_location_, 1, &data_.surface_normal.x);
}

}  // namespace palpate::gl
