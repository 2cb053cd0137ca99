// The examples built against the installed package (find_package(palpate)) and run headless: the plain
// application draws its sphere, and its deformed twin differs from it only where palpate's dent reaches.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const {
    return &rgb[3 * (std::size_t(y) * std::size_t(width) + std::size_t(x))];
  }
};

Image load(const std::filesystem::path& file) {
  Image image;
  int channels = 0;
  unsigned char* pixels = stbi_load(file.c_str(), &image.width, &image.height, &channels, 3);
  if (pixels) image.rgb.assign(pixels, pixels + 3 * image.width * image.height);
  stbi_image_free(pixels);
  return image;
}

TEST(Install, ExamplesBuiltAgainstTheInstalledPackageDrawAndDentWhereTheyShould) {
  const auto work = test::binary_dir() / "examples-test";
  const auto result = test::run_command(
      "cmake -D BUILD_DIR=" + test::binary_dir().string() +
      " -D EXAMPLES_DIR=" + (test::source_dir() / "examples").string() + " -D WORK_DIR=" + work.string() +
      " -D GENERATOR=" + PALPATE_GENERATOR + " -D BUILD_TYPE=" + PALPATE_BUILD_TYPE +
      " '-D CXX_FLAGS=" + PALPATE_CXX_FLAGS + "' '-D LINKER_FLAGS=" + PALPATE_LINKER_FLAGS + "' -P " +
      (test::source_dir() / "examples/build_against_install.cmake").string());
  ASSERT_EQ(result.exit_status, 0) << result.both();
  const Image plain = load(work / "existing_app.png"), deformed = load(work / "existing_app_deformed.png");
  ASSERT_GT(plain.width, 0);
  ASSERT_EQ(plain.width, deformed.width);
  ASSERT_EQ(plain.height, deformed.height);

  // The examples' camera and dent (existing_app_deformed.cpp): the contact point's pixel and how far
  // its 4-sigma reach (28 mm) spreads on screen.
  const glm::mat4 view_projection =
      glm::perspective(glm::radians(40.0f), float(plain.width) / float(plain.height), 10.0f, 500.0f) *
      glm::lookAt(glm::vec3(0, -170, 40), glm::vec3(0), glm::vec3(0, 0, 1));
  const auto pixel_of = [&](glm::vec3 p) {
    const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
    return glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * float(plain.width),
                     (0.5f - clip.y / clip.w * 0.5f) * float(plain.height));  // PNG rows from the top
  };
  const glm::vec3 contact = glm::normalize(glm::vec3(0.2f, -1.0f, 0.35f)) * 50.0f;
  const glm::vec2 centre = pixel_of(contact);
  float reach_px = 0.0f;
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
    reach_px = std::max(reach_px, glm::distance(pixel_of(contact + axis * 28.0f), centre));
  }

  int sphere = 0, near = 0, far = 0;
  for (int y = 0; y < plain.height; ++y) {
    for (int x = 0; x < plain.width; ++x) {
      const unsigned char *a = plain.at(x, y), *b = deformed.at(x, y);
      sphere += std::abs(a[0] - 26) + std::abs(a[1] - 26) + std::abs(a[2] - 31) >
                30;  // not the (0.1, 0.1, 0.12) clear
      const int difference = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
      if (difference <= 6) continue;
      (glm::distance(glm::vec2(x, y), centre) <= reach_px * 1.1f + 3.0f ? near : far) += 1;
    }
  }
  EXPECT_GT(sphere, plain.width * plain.height / 10) << "the plain example drew no sphere";
  EXPECT_GT(near, 100) << "the deformed example shows no dent around the contact";
  EXPECT_EQ(far, 0) << "the deformed example differs from the plain one beyond the dent's reach";
}

}  // namespace
}  // namespace palpate
