#include "palpate/core/scene_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/material.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

std::filesystem::path write_scene(const std::string& name, const std::string& text) {
  const auto dir = test::scratch_dir("scene_file_" + name);
  std::ofstream(dir / "scene.toml") << text;
  return dir / "scene.toml";
}

// Loads `text` and returns the error, failing the test if it loads.
Error load_error(const std::string& name, const std::string& text) {
  const auto file = write_scene(name, text);
  try {
    load_scene(file);
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), file) << e.what();
    return e;
  }
  ADD_FAILURE() << "scene " << name << " loaded but should not";
  return Error("none");
}

TEST(SceneFile, LoadsMeshesRelativeToTheFileWithMaterialsAndTransforms) {
  const auto file = write_scene("good", R"(# two objects
[[object]]
name = "ball"
mesh = "meshes/ball.ply"
translate = [10, 0, 0]
rotate_deg = [0, 0, 90]
sigma_mm = 6.5
stiffness_n_per_mm = 0.4
damping_ns_per_m = 2
color = [0.1, 0.2, 0.3]
touchable = false
falloff = "geodesic"

[[object]]
name = "brain"
mesh = "phantom:brain"
visible = false
)");
  std::filesystem::create_directories(file.parent_path() / "meshes");
  save_mesh(make_sphere(5.0f, 200), file.parent_path() / "meshes" / "ball.ply");
  const Scene scene = load_scene(file);
  ASSERT_EQ(scene.objects.size(), 2u);
  const SceneObject& ball = scene.objects[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.mesh.vertex_count(), 200u);
  EXPECT_FLOAT_EQ(ball.material.sigma_mm, 6.5f);
  EXPECT_FLOAT_EQ(ball.material.stiffness_n_per_mm, 0.4f);
  EXPECT_FLOAT_EQ(ball.material.damping_ns_per_m, 2.0f);
  EXPECT_EQ(ball.material.color, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FALSE(ball.material.touchable);
  EXPECT_TRUE(ball.material.visible);
  EXPECT_EQ(ball.material.falloff, Falloff::geodesic);
  EXPECT_EQ(scene.objects[1].material.falloff, Falloff::euclidean);  // the paper's, by default
  // Rotation about z by 90 degrees, then the translation: (1,0,0) goes to (10,1,0).
  const glm::vec3 moved = glm::vec3(ball.transform * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(moved.x, 10.0f, 1e-5f);
  EXPECT_NEAR(moved.y, 1.0f, 1e-5f);
  EXPECT_EQ(scene.objects[1].mesh.vertex_count(), brain_phantom_vertices);
  EXPECT_FALSE(scene.objects[1].material.visible);
}

// rotate_deg turns about x, then y, then z (fixed axes): R = Rz(60) Ry(45) Rx(30), worked by hand:
// (1, 2, 3) goes to (1.424704, 2.931761, 1.837117); then the translation.
TEST(SceneFile, RotatesAboutXThenYThenZ) {
  const auto file = write_scene("rotated", R"([[object]]
name = "box"
mesh = "phantom:skin"
translate = [1, -2, 0.5]
rotate_deg = [30, 45, 60]
)");
  const Scene scene = load_scene(file);
  const SceneObject& box = scene.objects[0];
  const glm::vec3 moved = glm::vec3(box.transform * glm::vec4(1, 2, 3, 1));
  EXPECT_NEAR(moved.x, 1.424704f + 1.0f, 1e-5f);
  EXPECT_NEAR(moved.y, 2.931761f - 2.0f, 1e-5f);
  EXPECT_NEAR(moved.z, 1.837117f + 0.5f, 1e-5f);
}

TEST(SceneFile, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(
      load_error("unknown_key", "[[object]]\nname = \"a\"\nmesh = \"phantom:skin\"\nsigma = 3\n").line(), 4);
  EXPECT_EQ(load_error("wrong_type", "[[object]]\nname = \"a\"\nmesh = \"phantom:skin\"\nvisible = \"yes\"\n")
                .line(),
            4);
  const Error range =
      load_error("range", "[[object]]\nname = \"a\"\nmesh = \"phantom:skin\"\n\nsigma_mm = -2\n");
  EXPECT_EQ(range.line(), 5);
  EXPECT_NE(std::string(range.what()).find("out of range"), std::string::npos);
  EXPECT_EQ(load_error("color", "[[object]]\nname = \"a\"\nmesh = \"phantom:skin\"\ncolor = [1, 2]\n").line(),
            4);
  const Error falloff =
      load_error("falloff", "[[object]]\nname = \"a\"\nmesh = \"phantom:skin\"\nfalloff = \"air\"\n");
  EXPECT_EQ(falloff.line(), 4);
  EXPECT_NE(std::string(falloff.what()).find("\"euclidean\" or \"geodesic\""), std::string::npos);
  EXPECT_EQ(load_error("syntax", "[[object]]\nname = \"a\nmesh = 1\n").line(), 2);
  EXPECT_EQ(load_error("top_key", "title = \"x\"\n").line(), 1);
  const Error missing = load_error("missing_mesh", "[[object]]\nname = \"a\"\nmesh = \"nowhere.ply\"\n");
  EXPECT_EQ(missing.line(), 1);
  EXPECT_NE(std::string(missing.what()).find("nowhere.ply"), std::string::npos);
  EXPECT_NE(std::string(load_error("no_objects", "# empty\n").what()).find("no [[object]]"),
            std::string::npos);
  EXPECT_NE(std::string(load_error("no_name", "[[object]]\nmesh = \"phantom:skin\"\n").what()).find("'name'"),
            std::string::npos);
}

TEST(SceneFile, MissingFileIsAnErrorNamingIt) {
  const std::filesystem::path file = test::scratch_dir("scene_missing") / "absent.toml";
  try {
    load_scene(file);
    FAIL() << "loaded a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), file);
  }
}

TEST(DefaultScene, IsThePapersBrainAndSkin) {
  const Scene scene = phantom_scene();
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.vertex_count(), 159063u);
  EXPECT_LT(scene.objects[0].material.sigma_mm, scene.objects[1].material.sigma_mm);
}

// save_scene writes what load_scene reads back: meshes beside the file, each transform (turned about
// all three axes and moved) and material as they were.
TEST(SceneFile, SavedScenesLoadBackTheSame) {
  Scene scene;
  SceneObject ball;
  ball.name = "ball";
  ball.mesh = make_sphere(10.0f, 300);
  ball.transform = glm::translate(glm::mat4(1.0f), glm::vec3(5, -6, 7));
  ball.transform = glm::rotate(ball.transform, 0.4f, glm::normalize(glm::vec3(1, 2, -3)));
  ball.material = skin_material;
  ball.material.touchable = false;
  ball.material.falloff = Falloff::geodesic;
  scene.objects.push_back(ball);
  SceneObject plain = ball;
  plain.name = "plain";
  plain.transform = glm::mat4(1.0f);
  plain.material = brain_material;
  plain.material.visible = false;
  scene.objects.push_back(plain);
  const auto file = test::scratch_dir("save_scene") / "nested" / "saved.toml";
  save_scene(scene, file);
  EXPECT_TRUE(std::filesystem::exists(file.parent_path() / "saved_ball.ply"));
  const Scene loaded = load_scene(file);
  ASSERT_EQ(loaded.objects.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const SceneObject &a = scene.objects[i], &b = loaded.objects[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.mesh.vertex_count(), b.mesh.vertex_count());
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(a.transform[c][r], b.transform[c][r], 1e-5f) << a.name;
    EXPECT_FLOAT_EQ(a.material.sigma_mm, b.material.sigma_mm);
    EXPECT_FLOAT_EQ(a.material.stiffness_n_per_mm, b.material.stiffness_n_per_mm);
    EXPECT_FLOAT_EQ(a.material.damping_ns_per_m, b.material.damping_ns_per_m);
    EXPECT_EQ(a.material.color, b.material.color);
    EXPECT_EQ(a.material.touchable, b.material.touchable);
    EXPECT_EQ(a.material.visible, b.material.visible);
    EXPECT_EQ(a.material.falloff, b.material.falloff);
  }
  scene.objects[0].transform[0][0] = 2.0f;  // scaled: not a rotation
  EXPECT_THROW(save_scene(scene, file), Error);
}

}  // namespace
}  // namespace palpate
