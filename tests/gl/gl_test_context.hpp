#pragma once
// One headless OpenGL 4.5 context (llvmpipe here) shared by the tests of this executable.
#include "palpate/gl/headless_context.hpp"

namespace palpate::test {

inline gl::HeadlessContext& gl_context() {
  static gl::HeadlessContext context;
  context.make_current();
  return context;
}

}  // namespace palpate::test
