#include "palpate/gl/stereo_compositor.hpp"

#include <epoxy/gl.h>

#include <string>

#include "current_context.hpp"
#include "palpate/core/error.hpp"
#include "palpate/gl/shader_program.hpp"

namespace palpate::gl {
namespace {

// One triangle over the whole output; each pixel fetched from its eye's target (no filtering: a
// squeezed eye was drawn squeezed).
constexpr const char* vertex_source = R"(#version 330 core
void main() {
  vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(corner, 0.0, 1.0);
}
)";

constexpr const char* fragment_source = R"(#version 330 core
uniform sampler2D left_eye;
uniform sampler2D right_eye;
uniform int mode;        // 0: left_eye alone, 1: side by side, 2: top and bottom, 3: anaglyph
uniform ivec2 mirror;    // 1 where that axis is flipped
uniform ivec2 split;     // side by side: the right eye's first column; top and bottom: the left eye's first row
uniform ivec2 size;      // of the output
uniform mat3 dubois_left;
uniform mat3 dubois_right;
out vec4 colour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (mirror.x == 1) p.x = size.x - 1 - p.x;
  if (mirror.y == 1) p.y = size.y - 1 - p.y;
  if (mode == 1) {
    colour = p.x < split.x ? texelFetch(left_eye, p, 0) : texelFetch(right_eye, ivec2(p.x - split.x, p.y), 0);
  } else if (mode == 2) {
    colour = p.y >= split.y ? texelFetch(left_eye, ivec2(p.x, p.y - split.y), 0) : texelFetch(right_eye, p, 0);
  } else if (mode == 3) {
    vec3 left = texelFetch(left_eye, p, 0).rgb, right = texelFetch(right_eye, p, 0).rgb;
    colour = vec4(clamp(dubois_left * left + dubois_right * right, 0.0, 1.0), 1.0);
  } else {
    colour = texelFetch(left_eye, p, 0);
  }
}
)";

// GLSL's mat3 is column-major: the transpose of a row-by-row matrix.
void set_rows(GLint location, const std::array<float, 9>& rows) {
  glUniformMatrix3fv(location, 1, GL_TRUE, rows.data());
}

// The caller's state that render() touches, put back when it ends.
class SavedState {
 public:
  SavedState() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
    for (int unit = 0; unit < 2; ++unit) {
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_[unit]);
    }
    glGetIntegerv(GL_DRAW_BUFFER, &draw_buffer_);
    for (int i = 0; i < 4; ++i) enabled_[i] = glIsEnabled(capabilities[i]);
    glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
  }
  ~SavedState() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_framebuffer_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_framebuffer_));
    glDrawBuffer(GLenum(draw_buffer_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glUseProgram(GLuint(program_));
    glBindVertexArray(GLuint(vertex_array_));
    for (int unit = 0; unit < 2; ++unit) {
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glBindTexture(GL_TEXTURE_2D, GLuint(texture_[unit]));
    }
    glActiveTexture(GLenum(active_texture_));
    for (int i = 0; i < 4; ++i) enabled_[i] ? glEnable(capabilities[i]) : glDisable(capabilities[i]);
    glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
  }
  SavedState(const SavedState&) = delete;
  SavedState& operator=(const SavedState&) = delete;

  GLint draw_framebuffer() const noexcept { return draw_framebuffer_; }

 private:
  static constexpr GLenum capabilities[4] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST};
  GLint draw_framebuffer_ = 0, read_framebuffer_ = 0, viewport_[4] = {}, program_ = 0, vertex_array_ = 0;
  GLint active_texture_ = GL_TEXTURE0, texture_[2] = {}, draw_buffer_ = GL_BACK;
  GLboolean enabled_[4] = {}, color_mask_[4] = {};
};

}  // namespace

StereoCompositor::StereoCompositor()
    : program_("palpate stereo compositor", vertex_source, fragment_source),
      uniforms_{program_.uniform("left_eye"),    program_.uniform("right_eye"),   program_.uniform("mode"),
                program_.uniform("mirror"),      program_.uniform("split"),       program_.uniform("size"),
                program_.uniform("dubois_left"), program_.uniform("dubois_right")} {
  glGenVertexArrays(1, &vertex_array_);  // a core profile draws nothing without one
}

StereoCompositor::~StereoCompositor() {
  if (!a_context_is_current()) return;
  for (Target& target : targets_) {
    glDeleteFramebuffers(1, &target.framebuffer);
    glDeleteTextures(1, &target.color);
    glDeleteRenderbuffers(1, &target.depth);
  }
  glDeleteVertexArrays(1, &vertex_array_);
}

bool StereoCompositor::stereo_buffers_available() noexcept {
  GLboolean stereo = GL_FALSE;
  glGetBooleanv(GL_STEREO, &stereo);
  return stereo == GL_TRUE;
}

void StereoCompositor::resize(Target& target, int width, int height) {
  if (target.framebuffer != 0 && target.width == width && target.height == height) return;
  if (target.framebuffer == 0) {
    glGenFramebuffers(1, &target.framebuffer);
    glGenTextures(1, &target.color);
    glGenRenderbuffers(1, &target.depth);
  }
  glBindTexture(GL_TEXTURE_2D, target.color);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindRenderbuffer(GL_RENDERBUFFER, target.depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.color, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, target.depth);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error("stereo compositor: the driver refused an eye target of " + std::to_string(width) + "x" +
                std::to_string(height) + " (framebuffer status 0x" + std::to_string(status) + ")");
  }
  target.width = width;
  target.height = height;
}

void StereoCompositor::render(StereoMode mode, Mirror mirror, int width, int height,
                              const std::function<void(const EyeTarget&)>& draw_eye) {
  if (width <= 0 || height <= 0) return;
  const SavedState saved;
  if (mode == StereoMode::quad_buffer && (saved.draw_framebuffer() != 0 || !stereo_buffers_available())) {
    throw Error(
        "quad-buffered stereo: the bound framebuffer has no left and right back buffers (a window with a "
        "stereo visual is needed; Mesa's drivers offer none)");
  }
  // Each eye's target: half the output side by side or top and bottom (the left eye gets the odd
  // pixel), the whole output otherwise.
  const bool stereo = mode != StereoMode::mono;
  const int left_width = mode == StereoMode::side_by_side ? width - width / 2 : width;
  const int left_height = mode == StereoMode::top_bottom ? height - height / 2 : height;
  const int right_width = mode == StereoMode::side_by_side ? width / 2 : width;
  const int right_height = mode == StereoMode::top_bottom ? height / 2 : height;
  const float aspect = float(width) / float(height);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  for (int i = 0; i < (stereo ? 2 : 1); ++i) {
    Target& target = targets_[std::size_t(i)];
    const Eye eye = !stereo ? Eye::centre : i == 0 ? Eye::left : Eye::right;
    resize(target, i == 0 ? left_width : right_width, i == 0 ? left_height : right_height);
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    glViewport(0, 0, target.width, target.height);
    draw_eye({eye, target.width, target.height, aspect});
  }

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(saved.draw_framebuffer()));
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glUseProgram(program_.id());
  glBindVertexArray(vertex_array_);
  for (int unit = 0; unit < 2; ++unit) {
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, targets_[std::size_t(stereo ? unit : 0)].color);
  }
  glUniform1i(uniforms_.left_eye, 0);
  glUniform1i(uniforms_.right_eye, 1);
  glUniform2i(uniforms_.mirror, mirror == Mirror::horizontal, mirror == Mirror::vertical);
  glUniform2i(uniforms_.split, left_width, right_height);
  glUniform2i(uniforms_.size, width, height);
  set_rows(uniforms_.dubois_left, dubois_left);
  set_rows(uniforms_.dubois_right, dubois_right);
  const GLint mode_uniform = uniforms_.mode;
  switch (mode) {
    case StereoMode::side_by_side:
      glUniform1i(mode_uniform, 1);
      break;
    case StereoMode::top_bottom:
      glUniform1i(mode_uniform, 2);
      break;
    case StereoMode::anaglyph:
      glUniform1i(mode_uniform, 3);
      break;
    case StereoMode::quad_buffer:  // each eye alone into its back buffer
      glUniform1i(mode_uniform, 0);
      glDrawBuffer(GL_BACK_LEFT);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, targets_[1].color);
      glDrawBuffer(GL_BACK_RIGHT);
      break;
    case StereoMode::mono:
      glUniform1i(mode_uniform, 0);
      break;
  }
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace palpate::gl
