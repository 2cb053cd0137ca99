#include "palpate/gl/framebuffer.hpp"

#include <epoxy/gl.h>

#include <string>

#include "current_context.hpp"
#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

GLenum internal_format(ColorFormat format) {
  switch (format) {
    case ColorFormat::rgba16f:
      return GL_RGBA16F;
    case ColorFormat::rgba32f:
      return GL_RGBA32F;
    case ColorFormat::rgba8:
      break;
  }
  return GL_RGBA8;
}

GLuint make_renderbuffer(GLenum format, int samples, int width, int height) {
  GLuint renderbuffer = 0;
  glCreateRenderbuffers(1, &renderbuffer);
  if (samples > 1) {
    glNamedRenderbufferStorageMultisample(renderbuffer, samples, format, width, height);
  } else {
    glNamedRenderbufferStorage(renderbuffer, format, width, height);
  }
  return renderbuffer;
}

void check_complete(GLuint framebuffer, const FramebufferParams& options) {
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error("framebuffer " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                " with " + std::to_string(options.samples) + " samples is incomplete (status 0x" +
                std::to_string(status) + ")");
  }
}

}  // namespace

Framebuffer::Framebuffer(FramebufferParams options) : options_(options) {
  if (options.width <= 0 || options.height <= 0) {
    throw Error("framebuffer: size must be positive, got " + std::to_string(options.width) + "x" +
                std::to_string(options.height));
  }
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (options.samples > max_samples) {
    throw Error("framebuffer: " + std::to_string(options.samples) + " samples asked, the driver allows " +
                std::to_string(max_samples));
  }
  const GLenum format = internal_format(options.color);
  color_ = make_renderbuffer(format, options.samples, options.width, options.height);
  depth_ = make_renderbuffer(GL_DEPTH_COMPONENT24, options.samples, options.width, options.height);
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferRenderbuffer(framebuffer_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glNamedFramebufferRenderbuffer(framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  check_complete(framebuffer_, options);
  if (options.samples > 1) {
    resolve_color_ = make_renderbuffer(format, 0, options.width, options.height);
    glCreateFramebuffers(1, &resolve_framebuffer_);
    glNamedFramebufferRenderbuffer(resolve_framebuffer_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                   resolve_color_);
    check_complete(resolve_framebuffer_, options);
  }
}

Framebuffer::~Framebuffer() {
  if (!a_context_is_current()) return;
  const GLuint framebuffers[] = {framebuffer_, resolve_framebuffer_};
  const GLuint renderbuffers[] = {color_, depth_, resolve_color_};
  glDeleteFramebuffers(2, framebuffers);
  glDeleteRenderbuffers(3, renderbuffers);
}

void Framebuffer::bind() const noexcept {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, options_.width, options_.height);
}

std::uint32_t Framebuffer::readable() const noexcept {
  if (!resolve_framebuffer_) return framebuffer_;
  glBlitNamedFramebuffer(framebuffer_, resolve_framebuffer_, 0, 0, options_.width, options_.height, 0, 0,
                         options_.width, options_.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return resolve_framebuffer_;
}

std::vector<std::uint8_t> Framebuffer::read_rgba8() const {
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(options_.width) * options_.height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, readable());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, options_.width, options_.height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  return pixels;
}

std::vector<float> Framebuffer::read_rgba_float() const {
  std::vector<float> pixels(static_cast<std::size_t>(options_.width) * options_.height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, readable());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, options_.width, options_.height, GL_RGBA, GL_FLOAT, pixels.data());
  return pixels;
}

}  // namespace palpate::gl
