// A host that includes palpate first and GLEW after it: palpate's headers leave GL to the host.
#include "palpate/palpate.hpp"
// palpate before GLEW, on purpose.
#include <GL/glew.h>
#include <gtest/gtest.h>

namespace palpate {
namespace {

TEST(IncludeOrder, PalpateThenGlewCompiles) {
  EXPECT_EQ(gl::dialect_of("#version 330 core\n"), gl::GlslDialect::uniform_block);
  EXPECT_NE(GLEW_VERSION, 0);  // GLEW's own header is in force
}

}  // namespace
}  // namespace palpate
