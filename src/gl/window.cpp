#include "palpate/gl/window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <mutex>

#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

// GLFW is process-wide: initialised with the first window, terminated with the last. A window that
// fails to open leaves it initialised: terminated, it closes the X connection, and an X server whose
// last client leaves resets, refusing the next connection for a moment (under Xvfb, the quad-buffer
// fallback's second window then failed 7 times in 16 with "Failed to open display").
std::mutex glfw_mutex;
int glfw_windows = 0;

std::string glfw_error() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  return code == GLFW_NO_ERROR ? std::string("no reason given")
                               : std::string(description ? description : "unknown") + " (GLFW error 0x" +
                                     std::to_string(code) + ")";
}

}  // namespace

struct Window::State {
  GLFWwindow* window = nullptr;
};

Window::Window(const WindowParams& options) : state_(std::make_unique<State>()) {
  const std::lock_guard lock(glfw_mutex);
  if (glfw_windows == 0 && !glfwInit()) throw Error("cannot open a window: glfwInit failed: " + glfw_error());
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, options.samples);
  glfwWindowHint(GLFW_STEREO, options.stereo ? GLFW_TRUE : GLFW_FALSE);
  state_->window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (!state_->window) {
    const std::string why = glfw_error();
    throw Error("cannot open a " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                " window with an OpenGL 4.5 core context" +
                (options.stereo ? std::string(" and left and right back buffers (stereo)") : std::string()) +
                ": " + why);
  }
  ++glfw_windows;
  glfwMakeContextCurrent(state_->window);
  glfwSwapInterval(options.vsync ? 1 : 0);
}

Window::~Window() {
  const std::lock_guard lock(glfw_mutex);
  glfwDestroyWindow(state_->window);
  if (--glfw_windows == 0) glfwTerminate();
}

void Window::make_current() const noexcept {
  glfwMakeContextCurrent(state_->window);
}
bool Window::should_close() const noexcept {
  return glfwWindowShouldClose(state_->window);
}
void Window::request_close() noexcept {
  glfwSetWindowShouldClose(state_->window, GLFW_TRUE);
}
void Window::swap_buffers() noexcept {
  glfwSwapBuffers(state_->window);
}
void Window::poll_events() noexcept {
  glfwPollEvents();
}

int Window::framebuffer_width() const noexcept {
  int width = 0, height = 0;
  glfwGetFramebufferSize(state_->window, &width, &height);
  return width;
}

int Window::framebuffer_height() const noexcept {
  int width = 0, height = 0;
  glfwGetFramebufferSize(state_->window, &width, &height);
  return height;
}

void* Window::native_handle() const noexcept {
  return state_->window;
}

}  // namespace palpate::gl
