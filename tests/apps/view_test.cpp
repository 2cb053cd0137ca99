// `palpate view` under Xvfb: it starts, draws the head, presses it through the haptic loop, takes a
// screenshot and quits cleanly.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

// `palpate view --scene phantom --width 800 --height 600 ARGUMENTS --screenshot` in a scratch folder
// under Xvfb; `screenshot` is where the picture goes.
test::CommandResult run_view(const std::string& folder, const std::string& arguments,
                             std::filesystem::path& screenshot) {
  const auto dir = test::scratch_dir(folder);
  screenshot = dir / "view.png";
  // In sanitizer builds: Mesa's GLX driver is unloaded at exit, so LeakSanitizer can neither name nor
  // suppress what it keeps; leaks of palpate's own code are checked by every other test.
  // Each test looks for a free display from its own number on: two `xvfb-run -a` started at once
  // can pick 99, and the second Xvfb then fails to start.
  const std::string first_display = std::to_string(100 + std::hash<std::string>{}(folder) % 800);
  return test::run_command(
      "cd " + dir.string() + " && ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" xvfb-run -a -n " +
      first_display + " -s '-screen 0 1024x768x24' " + std::string(PALPATE_CLI) +
      " view --scene phantom --width 800 --height 600 " + arguments + " --screenshot " + screenshot.string());
}

TEST(ViewCommand, RunsUnderXvfbAndTakesAScreenshot) {
  if (test::run_command("command -v xvfb-run").exit_status != 0) GTEST_SKIP() << "xvfb-run is not installed";
  std::filesystem::path shot;
  const auto run = run_view("view_command", "--frames 15 --press-depth 4", shot);
  ASSERT_EQ(run.exit_status, 0) << run.both();
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load(shot.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr) << run.both();
  EXPECT_EQ(width, 800);
  EXPECT_EQ(height, 600);
  // The head fills the middle of the window, lit in the skin's colour (linear 0.93, 0.76, 0.64): not the
  // background (0.08, 0.09, 0.11), not black. The panel covers the left 370 pixels.
  int skin = 0, sampled = 0;
  for (int y = height / 4; y < 3 * height / 4; y += 4) {
    for (int x = width / 2; x < 13 * width / 20; x += 4) {
      const stbi_uc* p = &pixels[3 * (y * width + x)];
      ++sampled;
      skin += p[0] > 60 && p[0] > p[1] && p[1] > p[2];
    }
  }
  stbi_image_free(pixels);
  EXPECT_GT(skin, sampled * 8 / 10) << skin << " of " << sampled << " pixels in the middle look like skin";
  // The tip was put 4 mm into the skin along the view ray through the centre: the haptic loop ran and
  // pushes back with k p, k = 0.8 N/mm, p the depth along the surface normal (4 mm times the cosine of
  // the ray's angle to it). The printout is the loop's last tick result.
  float depth = 0.0f, force = 0.0f;
  const auto line = run.out.find("palpate view: 15 frames; last tick: on 'skin', p = ");
  ASSERT_NE(line, std::string::npos) << run.both();
  ASSERT_EQ(
      std::sscanf(run.out.c_str() + line,
                  "palpate view: 15 frames; last tick: on 'skin', p = %f mm, |F| = %f N", &depth, &force),
      2)
      << run.both();
  EXPECT_GT(depth, 3.5f);
  EXPECT_LE(depth, 4.0f);
  EXPECT_NEAR(force, 0.8f * depth, 0.011f);
}

// Asked for quad-buffered stereo where the driver (Mesa) has no stereo visual: it says so and shows
// side by side instead, here mirrored left to right; the head is in the right half (the left eye's).
TEST(ViewCommand, QuadBufferedStereoFallsBackToSideBySideAndSaysSo) {
  if (test::run_command("command -v xvfb-run").exit_status != 0) GTEST_SKIP() << "xvfb-run is not installed";
  std::filesystem::path shot;
  const auto run = run_view("view_stereo", "--frames 5 --stereo quad-buffer --mirror horizontal", shot);
  ASSERT_EQ(run.exit_status, 0) << run.both();
  EXPECT_NE(run.err.find("quad-buffered stereo: the driver offers no stereo visual"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("palpate view: showing side-by-side instead of quad-buffered stereo"),
            std::string::npos)
      << run.err;
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load(shot.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr) << run.both();
  int skin = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = width / 2; x < width; ++x) {
      const stbi_uc* p = &pixels[3 * (y * width + x)];
      skin += p[0] > 60 && p[0] > p[1] && p[1] > p[2];
    }
  }
  stbi_image_free(pixels);
  EXPECT_GT(skin, width * height / 20) << "no head in the right half";
}

}  // namespace
}  // namespace palpate
