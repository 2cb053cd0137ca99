#include "gl_state_guard.hpp"

namespace palpate::gl {

GlStateGuard::GlStateGuard(GLuint uniform_binding) noexcept : uniform_binding_(uniform_binding) {
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_buffer_);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, uniform_binding, &indexed_uniform_buffer_);
  glGetInteger64i_v(GL_UNIFORM_BUFFER_START, uniform_binding, &indexed_uniform_start_);
  glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, uniform_binding, &indexed_uniform_size_);
  depth_test_ = glIsEnabled(GL_DEPTH_TEST);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  cull_face_ = glIsEnabled(GL_CULL_FACE);
  glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_mode_);
  glGetIntegerv(GL_FRONT_FACE, &front_face_);
  blend_ = glIsEnabled(GL_BLEND);
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode_);
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
}

GlStateGuard::~GlStateGuard() {
  glUseProgram(static_cast<GLuint>(program_));
  glBindVertexArray(static_cast<GLuint>(vertex_array_));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(array_buffer_));
  // An indexed binding made by glBindBufferBase reads back with size 0.
  if (indexed_uniform_size_ > 0) {
    glBindBufferRange(GL_UNIFORM_BUFFER, uniform_binding_, static_cast<GLuint>(indexed_uniform_buffer_),
                      static_cast<GLintptr>(indexed_uniform_start_),
                      static_cast<GLsizeiptr>(indexed_uniform_size_));
  } else {
    glBindBufferBase(GL_UNIFORM_BUFFER, uniform_binding_, static_cast<GLuint>(indexed_uniform_buffer_));
  }
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(uniform_buffer_));  // after: binding an index sets it
  depth_test_ ? glEnable(GL_DEPTH_TEST) : glDisable(GL_DEPTH_TEST);
  glDepthMask(depth_mask_);
  glDepthFunc(static_cast<GLenum>(depth_func_));
  cull_face_ ? glEnable(GL_CULL_FACE) : glDisable(GL_CULL_FACE);
  glCullFace(static_cast<GLenum>(cull_face_mode_));
  glFrontFace(static_cast<GLenum>(front_face_));
  blend_ ? glEnable(GL_BLEND) : glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygon_mode_[0]));
  glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
}

}  // namespace palpate::gl
