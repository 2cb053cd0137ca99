#pragma once
// A desktop window with an OpenGL 4.5 core context (GLFW inside; the header does not expose it).
// Creating one without a display, or on a driver without OpenGL 4.5, throws palpate::Error with GLFW's
// reason.
#include <memory>
#include <string>

namespace palpate::gl {

struct WindowParams {
  int width = 1280;
  int height = 1024;
  std::string title = "palpate";
  bool vsync = true;
  int samples = 4;      // multisampling of the default framebuffer; 0 for none
  bool stereo = false;  // left and right back buffers (quad-buffered stereo); throws where none is offered
};

class Window {
 public:
  // Opens the window and makes its context current on the calling thread.
  explicit Window(const WindowParams& options);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  void make_current() const noexcept;
  bool should_close() const noexcept;
  void request_close() noexcept;
  void swap_buffers() noexcept;
  // Processes pending window events (call once a frame).
  static void poll_events() noexcept;
  // Framebuffer size in pixels (differs from the window size on high-DPI screens).
  int framebuffer_width() const noexcept;
  int framebuffer_height() const noexcept;
  // The native GLFWwindow*, for callers that add their own input handling (e.g. an ImGui backend).
  void* native_handle() const noexcept;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace palpate::gl
