#pragma once
// The OpenGL context of a command: a window when there is a display and it is wanted, else headless EGL.
#include <memory>
#include <string>

#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/window.hpp"

namespace palpate::cli {

struct GlSession {
  std::unique_ptr<gl::HeadlessContext> headless;
  std::unique_ptr<gl::Window> window;  // null when headless
  std::string renderer;                // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  bool stereo_buffers = false;         // the window has left and right back buffers
};

// A window when `headless` is false and $DISPLAY or $WAYLAND_DISPLAY is set; headless EGL otherwise.
// With `stereo_buffers`, a window with left and right back buffers where the driver offers them; where
// it does not, a plain window and a line on stderr saying so.
GlSession open_gl(bool headless, int width, int height, const std::string& title,
                  bool stereo_buffers = false);

}  // namespace palpate::cli
