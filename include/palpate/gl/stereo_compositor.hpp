#pragma once
// Stereo output: draws a frame once per eye into offscreen targets and combines the two pictures into
// the framebuffer the caller has bound, in one of the layouts stereo displays take:
//   side_by_side  the left eye in the left half, each eye squeezed to half width (3D TVs' frame
//                 packing; a head-mounted viewer splits the screen the same way)
//   top_bottom    the left eye in the top half, each squeezed to half height
//   anaglyph      red-cyan, through Dubois' least-squares matrices (see dubois_left/right below)
//   quad_buffer   the left eye into GL_BACK_LEFT, the right into GL_BACK_RIGHT: needs a window with a
//                 stereo visual (Window's `stereo`); Mesa's drivers offer none
//   mono          the centre eye, for a mirror alone
// and, for any of them, the picture mirrored about the vertical or horizontal axis, for displays seen
// in a half-silvered mirror (ImmersiveTouch, the paper's system).
//
// The eyes' matrices come from palpate::StereoCamera; the callback draws with them. Needs a current
// OpenGL 3.3 context (core or compatibility); the caller's framebuffer bindings, viewport, program,
// vertex array, texture units 0-1, draw buffer and capabilities are left as found. Throws
// palpate::Error when the driver refuses a target or the shader. An application on older OpenGL uses
// StereoCamera alone, with its own viewports or back buffers.
#include <array>
#include <cstdint>
#include <functional>

#include "palpate/core/stereo_camera.hpp"
#include "palpate/gl/shader_program.hpp"

namespace palpate::gl {

enum class StereoMode { mono, side_by_side, top_bottom, anaglyph, quad_buffer };
enum class Mirror { none, horizontal, vertical };  // horizontal: left and right swap places

// Dubois' red-cyan matrices (E. Dubois, "A projection method to generate anaglyph stereo images",
// ICASSP 2001; the coefficients he published for red-cyan glasses), row by row: anaglyph RGB =
// clamp(left * L + right * R) on the stored (gamma-encoded) values, as common players apply them.
inline constexpr std::array<float, 9> dubois_left{0.456f,  0.500f,  0.176f,  -0.040f, -0.038f,
                                                  -0.016f, -0.015f, -0.021f, -0.005f};
inline constexpr std::array<float, 9> dubois_right{-0.043f, -0.088f, -0.002f, 0.378f, 0.734f,
                                                   -0.018f, -0.072f, -0.113f, 1.226f};

// What the callback draws into: its framebuffer is bound and the viewport covers it when called.
struct EyeTarget {
  Eye eye = Eye::centre;
  int width = 0, height = 0;  // pixels of this eye's target
  float aspect = 1.0f;        // the picture's width / height to project with (the whole output's)
};

class StereoCompositor {
 public:
  StereoCompositor();
  ~StereoCompositor();
  StereoCompositor(const StereoCompositor&) = delete;
  StereoCompositor& operator=(const StereoCompositor&) = delete;

  // One frame of `width` x `height` pixels: `draw_eye` once per eye the mode needs (left then right;
  // the centre eye for mono), each to clear and draw its picture, then the combination into the
  // framebuffer bound at the call, at (0, 0). Throws palpate::Error for quad_buffer where the bound
  // framebuffer has no left and right back buffers.
  void render(StereoMode mode, Mirror mirror, int width, int height,
              const std::function<void(const EyeTarget&)>& draw_eye);

  // Whether the framebuffer bound now has left and right back buffers (GL_STEREO).
  static bool stereo_buffers_available() noexcept;

 private:
  struct Target {
    std::uint32_t framebuffer = 0, color = 0, depth = 0;
    int width = 0, height = 0;
  };
  void resize(Target& target, int width, int height);

  std::array<Target, 2> targets_{};
  ShaderProgram program_;
  struct Uniforms {  // the combining shader's uniform locations, looked up once
    std::int32_t left_eye, right_eye, mode, mirror, split, size, dubois_left, dubois_right;
  } uniforms_;
  std::uint32_t vertex_array_ = 0;
};

}  // namespace palpate::gl
