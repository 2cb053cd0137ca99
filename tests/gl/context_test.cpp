// Contexts: a headless 4.5 core context exists, and one that cannot be made is a clear error.
#include <epoxy/gl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "gl_test_context.hpp"
#include "palpate/core/error.hpp"
#include "palpate/gl/window.hpp"

namespace palpate::gl {
namespace {

TEST(HeadlessContext, IsOpenGl45Core) {
  const HeadlessContext& context = test::gl_context();
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_EQ(major, 4);
  EXPECT_GE(minor, 5);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_THAT(context.platform(), testing::StartsWith("EGL"));
}

TEST(HeadlessContext, ImpossibleVersionIsAClearError) {
  test::gl_context();
  try {
    HeadlessContext impossible({9, 9});
    FAIL() << "an OpenGL 9.9 context was created";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_THAT(message, testing::HasSubstr("OpenGL 9.9 core"));
    EXPECT_THAT(message, testing::HasSubstr("tried:"));
    EXPECT_THAT(message, testing::HasSubstr("refused"));  // each attempt says why it failed
  }
  // The shared context still works afterwards.
  test::gl_context();
  GLint major = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  EXPECT_EQ(major, 4);
}

TEST(HeadlessContext, TwoContextsCoexist) {
  test::gl_context();
  {
    HeadlessContext second;
    GLint major = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    EXPECT_EQ(major, 4);
  }
  test::gl_context();
  EXPECT_NE(glGetString(GL_RENDERER), nullptr);
}

TEST(Window, WithoutADisplayIsAClearError) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display && *display) || (wayland && *wayland)) GTEST_SKIP() << "a display is present";
  try {
    Window window(WindowParams{});
    FAIL() << "a window opened without a display";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("cannot"));
    EXPECT_THAT(e.what(), testing::HasSubstr("GLFW"));
  }
  test::gl_context();
}

}  // namespace
}  // namespace palpate::gl
