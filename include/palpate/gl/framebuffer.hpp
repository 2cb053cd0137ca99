#pragma once
// An offscreen render target: a colour and a depth attachment, optionally multisampled (then resolved
// into a single-sample copy for reading). Needs a current OpenGL 4.5 context; throws palpate::Error
// when the driver refuses the combination.
#include <cstdint>
#include <vector>

namespace palpate::gl {

enum class ColorFormat {
  rgba8,    // display colours, PNG capture
  rgba16f,  // debug output of values in [-1, 1] (normals) at half precision
  rgba32f,  // debug output at full precision
};

struct FramebufferParams {
  int width = 1280;
  int height = 1024;
  ColorFormat color = ColorFormat::rgba8;
  int samples = 0;  // 0 or 1: single-sample; more: multisampled, resolved on read
};

class Framebuffer {
 public:
  explicit Framebuffer(FramebufferParams options);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  // Binds it as GL_FRAMEBUFFER and sets the viewport to cover it (the caller's state is not saved).
  void bind() const noexcept;
  std::uint32_t id() const noexcept { return framebuffer_; }
  int width() const noexcept { return options_.width; }
  int height() const noexcept { return options_.height; }
  const FramebufferParams& options() const noexcept { return options_; }

  // The colour attachment, bottom row first, 4 channels a pixel (resolving first if multisampled).
  // Allocates. Leaves GL_READ_FRAMEBUFFER bound to this framebuffer's readable copy.
  std::vector<std::uint8_t> read_rgba8() const;
  std::vector<float> read_rgba_float() const;

 private:
  std::uint32_t readable() const noexcept;

  FramebufferParams options_;
  std::uint32_t framebuffer_ = 0, color_ = 0, depth_ = 0;
  std::uint32_t resolve_framebuffer_ = 0, resolve_color_ = 0;  // only when multisampled
};

}  // namespace palpate::gl
