#include "palpate/gl/headless_context.hpp"

#include <epoxy/egl.h>

#include <string>
#include <vector>

#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error " + std::to_string(code);
  }
}

}  // namespace

struct HeadlessContext::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string platform;
};

namespace {

// Initialises `display` and creates a core context on it; on failure returns why.
std::string try_display(EGLDisplay display, const HeadlessContextParams& options,
                        HeadlessContext::State& out) {
  if (display == EGL_NO_DISPLAY) return "no display (" + egl_error_name(eglGetError()) + ")";
  EGLint major = 0, minor = 0;
  // An EGL display is one per device and process: it stays initialised for the life of the process
  // (terminating it would end the other contexts on it, and unloads the driver).
  if (!eglInitialize(display, &major, &minor))
    return "eglInitialize failed (" + egl_error_name(eglGetError()) + ")";
  if (!epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
    return "EGL_KHR_surfaceless_context is missing";
  }
  if (!eglBindAPI(EGL_OPENGL_API))
    return "eglBindAPI(EGL_OPENGL_API) failed (" + egl_error_name(eglGetError()) + ")";

  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &config_count) || config_count < 1) {
    if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context"))
      return "no OpenGL-renderable EGL config";
    config = EGL_NO_CONFIG_KHR;
  }
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       options.major_version,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       options.minor_version,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       options.compatibility ? EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT
                                                             : EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) {
    return "eglCreateContext for OpenGL " + std::to_string(options.major_version) + "." +
           std::to_string(options.minor_version) + (options.compatibility ? " compatibility" : " core") +
           " refused (" + egl_error_name(eglGetError()) + ")";
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    const std::string why = "eglMakeCurrent failed (" + egl_error_name(eglGetError()) + ")";
    eglDestroyContext(display, context);
    return why;
  }
  out.display = display;
  out.context = context;
  return {};
}

}  // namespace

HeadlessContext::HeadlessContext(HeadlessContextParams options) : state_(std::make_unique<State>()) {
  std::vector<std::string> attempts;
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLint count = 0;
    eglQueryDevicesEXT(0, nullptr, &count);
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
    if (count == 0) attempts.push_back("EGL device platform: no EGL devices");
    for (EGLint i = 0; i < count && state_->context == EGL_NO_CONTEXT; ++i) {
      const char* extensions = eglQueryDeviceStringEXT(devices[static_cast<std::size_t>(i)], EGL_EXTENSIONS);
      const std::string name =
          "EGL device " + std::to_string(i) + " (" + (extensions ? extensions : "") + ")";
      const EGLDisplay display =
          eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
      if (std::string why = try_display(display, options, *state_); why.empty()) {
        state_->platform = name;
      } else {
        attempts.push_back(name + ": " + why);
      }
    }
  } else {
    attempts.push_back("EGL device platform: EGL_EXT_platform_device is missing");
  }
  if (state_->context == EGL_NO_CONTEXT) {
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
      const EGLDisplay display =
          eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (std::string why = try_display(display, options, *state_); why.empty()) {
        state_->platform = "EGL Mesa surfaceless";
      } else {
        attempts.push_back("EGL Mesa surfaceless: " + why);
      }
    } else {
      attempts.push_back("EGL Mesa surfaceless: EGL_MESA_platform_surfaceless is missing");
    }
  }
  if (state_->context == EGL_NO_CONTEXT) {
    std::string message = "cannot create a headless OpenGL " + std::to_string(options.major_version) + "." +
                          std::to_string(options.minor_version) +
                          (options.compatibility ? " compatibility" : " core") + " context over EGL; tried:";
    for (const std::string& attempt : attempts) message += "\n  " + attempt;
    throw Error(message);
  }
}

HeadlessContext::~HeadlessContext() {
  if (eglGetCurrentContext() == state_->context) {
    eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(state_->display, state_->context);
}

void HeadlessContext::make_current() const {
  if (!eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) {
    throw Error("headless context (" + state_->platform + "): eglMakeCurrent failed (" +
                egl_error_name(eglGetError()) + ")");
  }
}

void HeadlessContext::release() const noexcept {
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

const std::string& HeadlessContext::platform() const noexcept {
  return state_->platform;
}

}  // namespace palpate::gl
