#pragma once
// One headless OpenGL 4.5 context (llvmpipe here) shared by the tests of this executable; the tests
// call OpenGL through libepoxy.
#include <epoxy/gl.h>

#include "palpate/gl/headless_context.hpp"

namespace palpate::test {

inline gl::HeadlessContext& gl_context() {
  static gl::HeadlessContext context;
  context.make_current();
  return context;
}

}  // namespace palpate::test
