// A GLEW host includes GLEW first, then palpate: nothing of palpate's pulls in another GL header or
// loader (GLEW stops the build with "gl.h included before glew.h" if one does).
#include <GL/glew.h>
// GLEW before palpate, on purpose.
#include <gtest/gtest.h>

#include <type_traits>

#include "palpate/palpate.hpp"

namespace palpate {
namespace {

TEST(IncludeOrder, GlewThenPalpateCompilesAndSharesTheHostsGlTypes) {
  static_assert(std::is_same_v<GLuint, std::uint32_t>, "palpate's GL names are the host's GLuint");
  EXPECT_EQ(gl::dialect_of("#version 120\n"), gl::GlslDialect::uniform_arrays);
}

}  // namespace
}  // namespace palpate
