#include "current_context.hpp"

#include <epoxy/egl.h>
#include <epoxy/glx.h>

namespace palpate::gl {

bool a_context_is_current() noexcept {
  return eglGetCurrentContext() != EGL_NO_CONTEXT || glXGetCurrentContext() != nullptr;
}

}  // namespace palpate::gl
