// Shader compile and link errors carry the driver's log and the program's name.
#include "palpate/gl/shader_program.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gl_test_context.hpp"
#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

constexpr const char* good_vertex =
    "#version 450 core\nlayout(location = 0) in vec3 p;\nout vec3 v;\n"
    "void main() { v = p; gl_Position = vec4(p, 1.0); }\n";
constexpr const char* good_fragment =
    "#version 450 core\nin vec3 v;\nout vec4 c;\nvoid main() { c = vec4(v, 1.0); }\n";

TEST(ShaderProgram, LinksValidSources) {
  test::gl_context();
  const ShaderProgram program("good", good_vertex, good_fragment);
  EXPECT_NE(program.id(), 0u);
  EXPECT_EQ(program.name(), "good");
}

TEST(ShaderProgram, CompileErrorNamesTheProgramAndCarriesTheDriverLog) {
  test::gl_context();
  const char* broken = "#version 450 core\nvoid main() { gl_Position = vec4(undeclared_thing, 1.0); }\n";
  try {
    ShaderProgram program("probe overlay", broken, good_fragment);
    FAIL() << "a broken shader compiled";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("'probe overlay'"));
    EXPECT_THAT(e.what(), testing::HasSubstr("vertex shader failed to compile"));
    EXPECT_THAT(e.what(), testing::HasSubstr("undeclared_thing"));  // from the driver's log
  }
}

TEST(ShaderProgram, LinkErrorNamesTheProgramAndCarriesTheDriverLog) {
  test::gl_context();
  // The fragment stage reads an input that no vertex output feeds.
  const char* unmatched =
      "#version 450 core\nin vec3 never_written;\nout vec4 c;\n"
      "void main() { c = vec4(never_written, 1.0); }\n";
  try {
    ShaderProgram program("mismatched stages", good_vertex, unmatched);
    FAIL() << "mismatched stages linked";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("'mismatched stages' failed to link"));
    EXPECT_THAT(e.what(), testing::HasSubstr("never_written"));
  }
}

}  // namespace
}  // namespace palpate::gl
