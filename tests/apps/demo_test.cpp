// `palpate demo` as `make demo` runs it, shortened: its files, its report, and frames that show the dent
// where the contact is (compared with the same view rendered undeformed by the library).
#include <epoxy/gl.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cmath>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "palpate/core/load.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/renderer.hpp"
#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

const std::string cli = PALPATE_CLI;

glm::mat4 matrix(const nlohmann::json& values) {
  std::vector<float> v = values.get<std::vector<float>>();
  return glm::make_mat4(v.data());
}

glm::vec3 vec(const nlohmann::json& values) {
  return {values[0].get<float>(), values[1].get<float>(), values[2].get<float>()};
}

// Pixel position (x right, y up from the bottom row) of a world point.
glm::vec2 project(const glm::mat4& view_projection, glm::vec3 p, int width, int height) {
  const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * float(width), (ndc.y * 0.5f + 0.5f) * float(height)};
}

// One run of the demo serves both checks (ctest runs each test in a process of its own).
void expect_files_and_report(const std::filesystem::path& out, const test::CommandResult& result) {
  ASSERT_EQ(result.exit_status, 0) << result.both();
  EXPECT_NE(result.out.find("TABLE I"), std::string::npos) << result.both();
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "contact_sheet.png"));
  const bool video = std::filesystem::is_regular_file(out / "demo.mp4");
  if (!video) {
    ASSERT_TRUE(std::filesystem::is_directory(out / "frames"));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(out / "frames"),
                            std::filesystem::directory_iterator()),
              30);
  }
  std::ifstream file(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(file);
  EXPECT_FALSE(report["device"].get<std::string>().empty());
  ASSERT_GE(report["rows"].size(), 1u);
  for (const auto& row : report["rows"]) {
    EXPECT_FALSE(row["model"].get<std::string>().empty());
    EXPECT_GT(row["vertices"].get<int>(), 0);
    EXPECT_GT(row["faces"].get<int>(), 0);
    EXPECT_GT(row["graphics_fps"].get<double>(), 0.0);
    EXPECT_GT(row["haptics_hz"].get<double>(), 0.0);
    EXPECT_GE(row["contact_age_ms"]["p99"].get<double>(), row["contact_age_ms"]["p50"].get<double>());
  }
  EXPECT_EQ(report["rows"][0]["vertices"].get<int>(), 159063);
  EXPECT_EQ(report["frames"]["count"].get<int>(), 30);
}

// The deepest key frame against the same view rendered undeformed by the library.
void expect_dent_only_around_the_contact(const std::filesystem::path& out) {
  std::ifstream file(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(file);
  // The deepest key frame.
  const nlohmann::json* deepest = nullptr;
  for (const auto& key : report["key_frames"]) {
    if (key["contact"]["object"].get<int>() >= 0 &&
        (!deepest ||
         key["contact"]["depth_mm"].get<float>() > (*deepest)["contact"]["depth_mm"].get<float>())) {
      deepest = &key;
    }
  }
  ASSERT_NE(deepest, nullptr) << "no key frame in contact";
  const nlohmann::json& key = *deepest;
  ASSERT_GT(key["contact"]["depth_mm"].get<float>(), 1.0f);

  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load((out / key["file"].get<std::string>()).c_str(), &width, &height, &channels, 4);
  ASSERT_NE(pixels, nullptr);
  std::vector<std::uint8_t> frame(pixels, pixels + std::size_t(width) * std::size_t(height) * 4);
  stbi_image_free(pixels);

  // The same view, undeformed, rendered by the library.
  gl::HeadlessContext context;
  Scene scene = phantom_scene();
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    scene.objects[i].material.visible = key["visible"][i].get<bool>();
  gl::Renderer renderer;
  renderer.upload(scene);
  gl::Framebuffer target({.width = width, .height = height});
  target.bind();
  glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const glm::mat4 view = matrix(key["view"]), projection = matrix(key["projection"]);
  renderer.draw(view, projection, std::span<const Contact>(), {});
  std::vector<std::uint8_t> plain = target.read_rgba8();
  // PNG rows run top first; the framebuffer's bottom first.
  const auto frame_pixel = [&](int x, int y) {
    return &frame[(std::size_t(height - 1 - y) * std::size_t(width) + std::size_t(x)) * 4];
  };

  const glm::vec3 contact = vec(key["contact"]["point_mm"]);
  const int object = key["contact"]["object"].get<int>();
  const float reach_mm = 4.0f * scene.objects[std::size_t(object)].material.sigma_mm;
  const glm::vec2 centre = project(projection * view, contact, width, height);
  // The dent's reach on screen: the largest projection of a 4 sigma offset in any direction.
  float reach_px = 0.0f;
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
    reach_px =
        std::max(reach_px,
                 glm::distance(project(projection * view, contact + axis * reach_mm, width, height), centre));
  }
  int near_changed = 0, far_changed = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* a = frame_pixel(x, y);
      const std::uint8_t* b = &plain[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
      const int difference = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
      if (difference <= 12) continue;
      const float distance = glm::distance(glm::vec2(x, y), centre);
      (distance <= reach_px * 1.1f + 3.0f ? near_changed : far_changed) += 1;
    }
  }
  EXPECT_GT(near_changed, 50) << "the frame does not differ from the undeformed view around the contact";
  EXPECT_EQ(far_changed, 0) << "the frame differs from the undeformed view far from the contact";
}

TEST(DemoRun, WritesItsReportAndFramesThatShowTheDentAroundTheContactOnly) {
  const auto out = test::scratch_dir("demo_run");
  const auto result = test::run_command(
      cli + " demo --headless --scene phantom --frames 30 --width 480 --height 384 --out " + out.string());
  expect_files_and_report(out, result);
  if (result.exit_status == 0) expect_dent_only_around_the_contact(out);
}

// A user's own scene: an open, wavy sheet (no inside, no enclosing object). The demo aims its presses at
// what the camera sees of it.
std::filesystem::path write_sheet_scene(const std::filesystem::path& folder, bool touchable) {
  Mesh sheet = make_grid(200.0f, 60);
  for (glm::vec3& p : sheet.positions_mm) p.z = 6.0f * std::sin(p.x / 15.0f) * std::sin(p.y / 17.0f);
  compute_vertex_normals(sheet);
  save_mesh(sheet, folder / "sheet.ply");
  const auto scene = folder / "sheet.toml";
  std::ofstream(scene) << "[[object]]\nname = \"sheet\"\nmesh = \"sheet.ply\"\nsigma_mm = 8.0\ntouchable = "
                       << (touchable ? "true" : "false") << "\n";
  return scene;
}

TEST(DemoRun, PressesAnOpenSheetWhereTheCameraSeesIt) {
  const auto out = test::scratch_dir("demo_sheet");
  const auto scene = write_sheet_scene(out, true);
  const auto result =
      test::run_command(cli + " demo --headless --frames 40 --width 320 --height 256 --scene " +
                        scene.string() + " --out " + (out / "run").string());
  ASSERT_EQ(result.exit_status, 0) << result.both();
  std::ifstream file(out / "run" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(file);
  bool pressed = false;
  for (const auto& key : report["key_frames"]) pressed |= key["contact"]["depth_mm"].get<float>() > 1.0f;
  EXPECT_TRUE(pressed) << "no key frame shows the probe pressing the sheet";
}

TEST(DemoRun, ASceneWithNothingToPressSaysSoInOneLine) {
  const auto out = test::scratch_dir("demo_untouchable");
  const auto scene = write_sheet_scene(out, false);
  const auto result = test::run_command(cli + " demo --headless --frames 5 --scene " + scene.string() +
                                        " --out " + (out / "run").string());
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_EQ(result.err,
            "palpate: error: the scene has no object that is visible and touchable: nothing for the probe to "
            "press\n");
}

// Top and bottom stereo: each key frame holds the left eye's picture above the right eye's, each
// squeezed to half height: the same head in both, seen from 63 mm apart.
TEST(DemoRun, TopBottomStereoFramesHoldBothEyes) {
  const auto out = test::scratch_dir("demo_stereo");
  const auto result =
      test::run_command(cli +
                        " demo --headless --scene phantom --frames 6 --width 320 --height 256 "
                        "--stereo top-bottom --out " +
                        out.string());
  ASSERT_EQ(result.exit_status, 0) << result.both();
  EXPECT_NE(result.out.find("stereo top-bottom, mirror none, eyes 63 mm apart"), std::string::npos)
      << result.out;
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load((out / "keyframe_0.png").c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr);
  int lit[2] = {0, 0}, differ = 0;
  for (int y = 0; y < height / 2; ++y) {
    for (int x = 0; x < width; ++x) {
      const stbi_uc* top = &pixels[3 * (y * width + x)];
      const stbi_uc* bottom = &pixels[3 * ((y + height / 2) * width + x)];
      lit[0] += top[0] > 60;
      lit[1] += bottom[0] > 60;
      differ += std::abs(top[0] - bottom[0]) > 30;
    }
  }
  stbi_image_free(pixels);
  EXPECT_GT(lit[0], width * height / 20);
  EXPECT_NEAR(lit[0], lit[1], 0.1 * lit[0]) << "the two eyes see different amounts of the head";
  EXPECT_GT(differ, 20) << "the two eyes see the same picture: no parallax";
}

}  // namespace
}  // namespace palpate
