#include "gl_session.hpp"

#include <epoxy/gl.h>

#include <cstdio>
#include <cstdlib>

#include "palpate/core/error.hpp"

namespace palpate::cli {

GlSession open_gl(bool headless, int width, int height, const std::string& title, bool stereo_buffers) {
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
    if (stereo_buffers) {
      options.stereo = true;
      try {
        session.window = std::make_unique<gl::Window>(options);
        session.stereo_buffers = true;
      } catch (const Error& error) {
        std::fprintf(stderr, "%s: quad-buffered stereo: the driver offers no stereo visual (%s)\n",
                     title.c_str(), error.what());
        options.stereo = false;
      }
    }
    if (!session.window) session.window = std::make_unique<gl::Window>(options);
  } else {
    session.headless = std::make_unique<gl::HeadlessContext>();
  }
  session.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return session;
}

}  // namespace palpate::cli
