// A libepoxy host: epoxy first, then palpate, in one translation unit.
#include <epoxy/gl.h>
// epoxy before palpate, on purpose.
#include <gtest/gtest.h>

#include "palpate/palpate.hpp"

namespace palpate {
namespace {

TEST(IncludeOrder, EpoxyThenPalpateCompiles) {
  const std::string source = gl::insert_deform_glsl("#version 450 core\nvoid main() {}\n");
  EXPECT_NE(source.find("PalpateDeform"), std::string::npos);
  EXPECT_EQ(GL_UNIFORM_BUFFER, 0x8A11);  // epoxy's own header is in force
}

}  // namespace
}  // namespace palpate
