// Offscreen targets and PNG capture: what is drawn is what is read back and what the file holds.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <vector>

#include "gl_test_context.hpp"
#include "palpate/core/error.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/png.hpp"
#include "test_paths.hpp"

namespace palpate::gl {
namespace {

// Clears the bottom half of `target` to one colour and the top half to another.
void paint_halves(const Framebuffer& target) {
  target.bind();
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, target.height() / 2, target.width(), target.height() / 2);
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
}

TEST(Framebuffer, ReadsBackWhatWasDrawnBottomRowFirst) {
  test::gl_context();
  for (int samples : {0, 4}) {
    const Framebuffer target({64, 32, ColorFormat::rgba8, samples});
    paint_halves(target);
    const std::vector<std::uint8_t> pixels = target.read_rgba8();
    ASSERT_EQ(pixels.size(), 64u * 32u * 4u);
    EXPECT_THAT(std::vector<std::uint8_t>(pixels.begin(), pixels.begin() + 4),
                testing::ElementsAre(255, 0, 0, 255));
    EXPECT_THAT(std::vector<std::uint8_t>(pixels.end() - 4, pixels.end()),
                testing::ElementsAre(0, 0, 255, 255));
  }
  const Framebuffer floats({8, 8, ColorFormat::rgba32f});
  floats.bind();
  glClearColor(-0.25f, 0.5f, 0.75f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const std::vector<float> values = floats.read_rgba_float();
  EXPECT_THAT(std::vector<float>(values.begin(), values.begin() + 4),
              testing::ElementsAre(-0.25f, 0.5f, 0.75f, 1.0f));
}

TEST(Framebuffer, TooManySamplesIsAClearError) {
  test::gl_context();
  EXPECT_THAT(
      [] {
        Framebuffer target({16, 16, ColorFormat::rgba8, 4096});
      },
      testing::ThrowsMessage<Error>(testing::HasSubstr("4096 samples asked")));
}

TEST(SavePng, WritesTheImageTopRowFirst) {
  test::gl_context();
  const Framebuffer target({40, 20});
  paint_halves(target);
  const auto file = test::scratch_dir("png") / "halves.png";
  save_png(file, 40, 20, target.read_rgba8());
  int width = 0, height = 0, channels = 0;
  stbi_uc* image = stbi_load(file.c_str(), &width, &height, &channels, 4);
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(width, 40);
  EXPECT_EQ(height, 20);
  EXPECT_THAT(std::vector<std::uint8_t>(image, image + 4),
              testing::ElementsAre(0, 0, 255, 255));  // top: blue
  EXPECT_THAT(std::vector<std::uint8_t>(image + 40 * 20 * 4 - 4, image + 40 * 20 * 4),
              testing::ElementsAre(255, 0, 0, 255));
  stbi_image_free(image);
}

TEST(SavePng, BadSizeOrPathIsAClearError) {
  const std::vector<std::uint8_t> pixels(4 * 4 * 4, 0);
  EXPECT_THAT([&] { save_png("x.png", 5, 4, pixels); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("5x4")));
  EXPECT_THAT([&] { save_png("/nonexistent-folder/x.png", 4, 4, pixels); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("/nonexistent-folder/x.png")));
}

}  // namespace
}  // namespace palpate::gl
