#pragma once
// An OpenGL core context with no window, over EGL: for tests, benchmarks, servers and PNG capture.
// It first tries EGL_EXT_platform_device (each EGL device in turn: NVIDIA's driver, Mesa's llvmpipe
// and GPU drivers), then Mesa's surfaceless platform. The context has no default framebuffer: draw into
// a palpate::gl::Framebuffer. A context that cannot be created throws palpate::Error saying what was
// tried and why each attempt failed.
#include <memory>
#include <string>

namespace palpate::gl {

struct HeadlessContextParams {
  int major_version = 4;  // OpenGL version asked for
  int minor_version = 5;
  bool compatibility = false;  // the compatibility profile (GLSL 1.10/1.20, fixed-function state), not core
};

class HeadlessContext {
 public:
  // Creates the context and makes it current on the calling thread.
  explicit HeadlessContext(HeadlessContextParams options = {});
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // Makes the context current on the calling thread (throws palpate::Error on failure).
  void make_current() const;
  // Leaves no EGL context current on the calling thread, so that a GLX one (a toolkit's window) may be
  // made current there: a thread has one current context of one API at a time.
  void release() const noexcept;
  // How it was made, e.g. "EGL device 0 (EGL_MESA_device_software)" or "EGL Mesa surfaceless".
  const std::string& platform() const noexcept;

  struct State;  // EGL handles, defined in the .cpp

 private:
  std::unique_ptr<State> state_;
};

}  // namespace palpate::gl
