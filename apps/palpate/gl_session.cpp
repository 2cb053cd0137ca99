#include "gl_session.hpp"

#include <epoxy/gl.h>

#include <cstdlib>

namespace palpate::cli {

GlSession open_gl(bool headless, int width, int height, const std::string& title) {
  GlSession session;
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if (!headless && ((display && *display) || (wayland && *wayland))) {
    gl::WindowParams options;
    options.width = width;
    options.height = height;
    options.title = title;
    options.vsync = false;  // measure what the GPU can do, not the display's refresh
    options.samples = 0;
    session.window = std::make_unique<gl::Window>(options);
  } else {
    session.headless = std::make_unique<gl::HeadlessContext>();
  }
  session.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return session;
}

}  // namespace palpate::cli
