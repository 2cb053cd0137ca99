#pragma once
// Saves the OpenGL state that palpate's Renderer changes and restores it when it goes out of scope,
// as Dear ImGui's OpenGL 3 backend does around its draw: the host application's state is left as found.
#include <epoxy/gl.h>

namespace palpate::gl {

class GlStateGuard {
 public:
  // `uniform_binding`: the indexed GL_UNIFORM_BUFFER binding point the renderer binds.
  explicit GlStateGuard(GLuint uniform_binding) noexcept;
  ~GlStateGuard();
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

 private:
  GLuint uniform_binding_;
  GLint program_ = 0, vertex_array_ = 0, array_buffer_ = 0, uniform_buffer_ = 0;
  GLint indexed_uniform_buffer_ = 0;
  GLint64 indexed_uniform_start_ = 0, indexed_uniform_size_ = 0;
  GLboolean depth_test_ = GL_FALSE, depth_mask_ = GL_TRUE, cull_face_ = GL_FALSE, blend_ = GL_FALSE;
  GLint depth_func_ = GL_LESS, cull_face_mode_ = GL_BACK, front_face_ = GL_CCW;
  GLint polygon_mode_[2] = {GL_FILL, GL_FILL};
  GLboolean color_mask_[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
};

}  // namespace palpate::gl
