// `palpate view` under Xvfb: it starts, draws, takes a screenshot that is not empty, and quits cleanly.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <set>

#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

TEST(ViewCommand, RunsUnderXvfbAndTakesAScreenshot) {
  if (test::run_command("command -v xvfb-run").exit_status != 0) GTEST_SKIP() << "xvfb-run is not installed";
  const auto dir = test::scratch_dir("view_command");
  const auto shot = dir / "view.png";
  // In sanitizer builds: Mesa's GLX driver is unloaded at exit, so LeakSanitizer can neither name nor
  // suppress what it keeps; leaks of palpate's own code are checked by every other test.
  const auto run = test::run_command(
      "cd " + dir.string() +
      " && ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" xvfb-run -a -s '-screen 0 1024x768x24' " +
      std::string(PALPATE_CLI) + " view --width 800 --height 600 --frames 15 --press-depth 4 --screenshot " +
      shot.string());
  ASSERT_EQ(run.exit_status, 0) << run.output;
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load(shot.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr) << run.output;
  EXPECT_EQ(width, 800);
  EXPECT_EQ(height, 600);
  // Not empty: the background, the head and the panel give many distinct colours.
  std::set<int> colours;
  for (int i = 0; i < width * height; ++i)
    colours.insert(pixels[3 * i] << 16 | pixels[3 * i + 1] << 8 | pixels[3 * i + 2]);
  stbi_image_free(pixels);
  EXPECT_GT(colours.size(), 200u);
}

}  // namespace
}  // namespace palpate
