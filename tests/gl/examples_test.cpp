// The examples, built against the installed package as their kinds of host build (gl45_* and core33_*
// with find_package(palpate), legacy_* with a Makefile and pkg-config), run headless. For each host:
// the plain program draws its sphere; its deformed twin differs from it only within the dent's reach;
// and the twin's picture matches the plain program drawing palpate's CPU reference of the dented
// sphere (deform_mesh: displaced positions, exact normals of the deformed triangles), so the host's
// space (world mm, eye space in metres, doubles) and GLSL version (4.50, 3.30, 1.20) change nothing.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstdlib>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "palpate/core/deform.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"
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

int difference(const unsigned char* a, const unsigned char* b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

// What every example draws: a 50 mm sphere seen from (0, -170, 40) mm with a 40 degree field of view,
// and (the deformed ones) the dent 5 mm deep, sigma 7 mm, at this contact point.
const Dent example_dent{glm::normalize(glm::vec3(0.2f, -1.0f, 0.35f)) * 50.0f, 5.0f, 7.0f};

std::filesystem::path work() {
  return test::binary_dir() / "examples-test";
}

// GLFW needs a display: the test's own when it has one, else a virtual one.
// Under AddressSanitizer, GLFW's X and GLX teardown leaks 112 bytes in a driver already unloaded (no
// frames to suppress by); the plain core33 program, with no palpate GL code, leaks the same.
std::string display_prefix() {
  const std::string no_leak_check = "env ASAN_OPTIONS=detect_leaks=0 ";
  if (std::getenv("DISPLAY")) return no_leak_check;
  return std::system("command -v xvfb-run > /dev/null") == 0 ? "xvfb-run -a " + no_leak_check : "";
}

// Runs the host's plain program, its deformed twin and the plain one on the CPU reference mesh; hosts
// that draw no sphere of their own are given `sphere.ply`, the mesh the reference was made from.
void check(const std::string& host, bool needs_display, bool needs_sphere = false) {
  SCOPED_TRACE(host);
  const std::string prefix = needs_display ? display_prefix() : "";
  ASSERT_TRUE(!needs_display || !prefix.empty())
      << "GLFW and VTK need a display: no DISPLAY and no xvfb-run (scripts/install-deps.sh installs xvfb)";
  const auto program = [&](const std::string& name) {
    const auto build = work() / "build";
    return prefix + (std::filesystem::exists(build / name) ? build / name : build / "legacy" / name).string();
  };
  const auto plain_png = work() / (host + ".png"), deformed_png = work() / (host + "_deformed.png"),
             reference_png = work() / (host + "_reference.png");
  const std::string sphere_option = needs_sphere ? " --mesh " + (work() / "sphere.ply").string() : "";
  for (const auto& command :
       {program(host + "_app") + " --headless " + plain_png.string() + sphere_option,
        program(host + "_app_deformed") + " --headless " + deformed_png.string() + sphere_option,
        program(host + "_app") + " --headless " + reference_png.string() + " --mesh " +
            (work() / "reference.ply").string()}) {
    const auto result = test::run_command(command);
    ASSERT_EQ(result.exit_status, 0) << command << "\n" << result.both();
  }
  const Image plain = load(plain_png), deformed = load(deformed_png), reference = load(reference_png);
  ASSERT_GT(plain.width, 0);
  for (const Image* image : {&deformed, &reference}) {
    ASSERT_EQ(image->width, plain.width);
    ASSERT_EQ(image->height, plain.height);
  }

  // The contact point's pixel and how far its 4-sigma reach (28 mm) spreads on screen.
  const glm::mat4 view_projection =
      glm::perspective(glm::radians(40.0f), float(plain.width) / float(plain.height), 10.0f, 500.0f) *
      glm::lookAt(glm::vec3(0, -170, 40), glm::vec3(0), glm::vec3(0, 0, 1));
  const auto pixel_of = [&](glm::vec3 p) {
    const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
    return glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * float(plain.width),
                     (0.5f - clip.y / clip.w * 0.5f) * float(plain.height));  // PNG rows from the top
  };
  const glm::vec2 centre = pixel_of(example_dent.center_mm);
  float reach_px = 0.0f;
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    reach_px = std::max(reach_px, glm::distance(pixel_of(example_dent.center_mm + axis * 28.0f), centre));

  const unsigned char clear[] = {26, 26, 31};  // (0.1, 0.1, 0.12)
  int sphere = 0, near = 0, far = 0, worst_from_reference = 0;
  double reference_sum = 0.0;
  for (int y = 0; y < plain.height; ++y) {
    for (int x = 0; x < plain.width; ++x) {
      sphere += difference(plain.at(x, y), clear) > 30;
      const int from_reference = difference(deformed.at(x, y), reference.at(x, y));
      reference_sum += from_reference;
      worst_from_reference = std::max(worst_from_reference, from_reference);
      if (difference(plain.at(x, y), deformed.at(x, y)) <= 6) continue;
      (glm::distance(glm::vec2(x, y), centre) <= reach_px * 1.1f + 3.0f ? near : far) += 1;
    }
  }
  const double reference_mean = reference_sum / double(plain.width * plain.height);
  std::printf(
      "%s: sphere %d px, dent %d px (%d beyond its reach); against the CPU reference: "
      "mean %.3f, worst %d (of 765)\n",
      host.c_str(), sphere, near, far, reference_mean, worst_from_reference);
  EXPECT_GT(sphere, plain.width * plain.height / 10) << "the plain example drew no sphere";
  EXPECT_GT(near, 1000) << "the deformed example shows no dent around the contact";
  EXPECT_EQ(far, 0) << "the deformed example differs from the plain one beyond the dent's reach";
  // Measured here: mean 0.20, worst 17 for the GL hosts, mean 0.09, worst 9 for VTK (rasterisation of
  // a mesh made on the CPU).
  EXPECT_LT(reference_mean, 0.6) << "the deformed example does not look like the CPU reference";
  EXPECT_LE(worst_from_reference, 36) << "the deformed example does not look like the CPU reference";
}

// One test, so that the examples are built once (ctest runs each test in a process of its own).
TEST(Examples, EachHostDrawsAndDentsLikeTheCpuReference) {
  const auto built = test::run_command(
      "cmake -D BUILD_DIR=" + test::binary_dir().string() +
      " -D EXAMPLES_DIR=" + (test::source_dir() / "examples").string() + " -D WORK_DIR=" + work().string() +
      " -D GENERATOR=" + PALPATE_GENERATOR + " -D BUILD_TYPE=" + PALPATE_BUILD_TYPE +
      " '-D CXX_FLAGS=" + PALPATE_CXX_FLAGS + "' '-D LINKER_FLAGS=" + PALPATE_LINKER_FLAGS + "' -P " +
      (test::source_dir() / "examples/build_against_install.cmake").string());
  ASSERT_EQ(built.exit_status, 0) << built.both();
  const Mesh sphere = make_sphere(50.0f, 40000);
  Mesh reference;
  deform_mesh(sphere, glm::mat4(1.0f), {&example_dent, 1}, reference);
  save_mesh(sphere, work() / "sphere.ply");
  save_mesh(reference, work() / "reference.ply");

  check("gl45", false);      // OpenGL 4.5, palpate's own context and shader classes, world mm
  check("core33", true);     // OpenGL 3.3 core, GLFW, its own epoxy calls and framebuffer, world mm
  check("legacy", true);     // OpenGL 2.1, GLEW, GLSL 1.20, eye space in metres, doubles
  check("vtk", true, true);  // VTK 9.1: the actor's own shaders, VTK's lighting
  check("coin", true);       // Coin3D 4.0: a shader node in the scene graph, GLSL 1.20, Coin's lights
}

}  // namespace
}  // namespace palpate
