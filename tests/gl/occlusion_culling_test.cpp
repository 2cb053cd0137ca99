// The renderer's occlusion culling on llvmpipe, in the default scene (a brain inside a skin): from
// outside, the hidden brain is culled (the query's own result, read back) and the image is the same as
// without culling; wherever the brain shows (no skin, a camera inside the skin, a dent through the
// skin, a bump out through it) it is drawn, the image still the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <vector>

#include "gl_test_context.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/renderer.hpp"

namespace palpate::gl {
namespace {

constexpr int width = 640, height = 512;
constexpr int brain = 0, skin = 1;  // in phantom_scene()

struct Camera {
  glm::mat4 view, projection;
};

Camera camera(glm::vec3 eye, glm::vec3 target, float near_mm, glm::vec3 up = {0, 0, 1}) {
  return {glm::lookAt(eye, target, up),
          glm::perspective(glm::radians(40.0f), float(width) / float(height), near_mm, 2000.0f)};
}

// The whole head in view from `direction` (outside), as bench render frames it.
Camera outside(const Scene& scene, glm::vec3 direction) {
  const glm::vec3 center = world_bounds(scene).center_mm();
  const float distance = 0.5f * glm::length(world_bounds(scene).size_mm()) / std::sin(glm::radians(20.0f));
  return camera(center + distance * glm::normalize(direction), center, 0.05f * distance);
}

Scene default_scene_with(bool skin_visible) {
  Scene scene = phantom_scene();
  EXPECT_EQ(scene.objects[brain].name, "brain");
  EXPECT_EQ(scene.objects[skin].name, "skin");
  scene.objects[skin].material.visible = skin_visible;
  return scene;
}

struct Frame {
  std::vector<std::uint8_t> pixels;
  DrawResult result;
};

class SceneTarget {
 public:
  explicit SceneTarget(const Scene& scene) { renderer_.upload(scene); }

  Frame draw(const Camera& view, std::span<const ObjectDent> dents, bool culling) {
    target_.bind();
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    DrawParams options;
    options.occlusion_culling = culling;
    options.read_occlusion_results = true;
    Frame frame;
    frame.result = renderer_.draw(view.view, view.projection, dents, options);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    frame.pixels = target_.read_rgba8();
    return frame;
  }

  // The frame with culling, checked bit for bit against the frame without.
  Frame draw_checked(const Camera& view, std::span<const ObjectDent> dents = {}) {
    Frame culled = draw(view, dents, true);
    const Frame reference = draw(view, dents, false);
    EXPECT_EQ(reference.result.occlusion_tested, 0);
    EXPECT_TRUE(culled.pixels == reference.pixels) << "occlusion culling changed the image";
    return culled;
  }

 private:
  gl::HeadlessContext& context_ = test::gl_context();  // first: the members below need it current
  Framebuffer target_{{width, height}};
  Renderer renderer_;
};

std::size_t differing_pixels(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.size(); i += 4)
    count += !std::equal(a.begin() + long(i), a.begin() + long(i) + 4, b.begin() + long(i));
  return count;
}

std::size_t covered_pixels(const std::vector<std::uint8_t>& pixels) {
  std::size_t count = 0;
  for (std::size_t i = 3; i < pixels.size(); i += 4) count += pixels[i] != 0;
  return count;
}

// The skin vertex that reaches furthest toward `direction` from the scene's centre, where a dent there
// faces a camera placed along it.
glm::vec3 skin_point_toward(const Scene& scene, glm::vec3 direction) {
  const glm::vec3 center = world_bounds(scene).center_mm();
  const auto& positions = scene.objects[skin].mesh.positions_mm;
  return *std::max_element(positions.begin(), positions.end(), [&](glm::vec3 a, glm::vec3 b) {
    return glm::dot(a - center, direction) < glm::dot(b - center, direction);
  });
}

TEST(OcclusionCulling, FromOutsideTheHiddenBrainIsCulled) {
  const Scene scene = default_scene_with(true);
  SceneTarget target(scene);
  // The benchmark's view, then a ring around the head, above and below.
  std::vector<glm::vec3> directions{{0.15f, -1.0f, 0.35f}};
  for (int azimuth = 0; azimuth < 360; azimuth += 60) {
    for (float elevation : {-30.0f, 20.0f, 70.0f}) {
      const float a = glm::radians(float(azimuth)), e = glm::radians(elevation);
      directions.emplace_back(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    }
  }
  for (const glm::vec3& direction : directions) {
    SCOPED_TRACE(testing::Message() << "view from " << direction.x << ", " << direction.y << ", "
                                    << direction.z);
    const Frame frame = target.draw_checked(outside(scene, direction));
    EXPECT_EQ(frame.result.occlusion_tested, 1);
    EXPECT_EQ(frame.result.occlusion_culled, 1);
    EXPECT_GT(covered_pixels(frame.pixels), 20000u);
  }
}

TEST(OcclusionCulling, WithTheSkinInvisibleTheBrainIsDrawn) {
  const Scene scene = default_scene_with(false);
  SceneTarget target(scene);
  const Frame frame = target.draw_checked(outside(scene, {0.15f, -1.0f, 0.35f}));
  EXPECT_EQ(frame.result.occlusion_tested, 0);  // the first object drawn has nothing in front of it
  EXPECT_GT(covered_pixels(frame.pixels), 20000u);
}

TEST(OcclusionCulling, FromInsideTheSkinTheBrainIsDrawn) {
  const Scene scene = default_scene_with(true);
  const Scene brain_alone = default_scene_with(false);
  SceneTarget target(scene), reference(brain_alone);
  const auto& positions = scene.objects[brain].mesh.positions_mm;
  const float top = std::max_element(positions.begin(), positions.end(), [](glm::vec3 a, glm::vec3 b) {
                      return a.z < b.z;
                    })->z;

  // 5 mm over the top of the brain, in the gap under the skin, looking down: the query runs and passes
  // (the skin's inside faces away from the eye and is culled).
  const Camera down = camera({0.0f, 10.0f, top + 5.0f}, {0.0f, 10.0f, 0.0f}, 1.0f, {0, 1, 0});
  const Frame frame = target.draw_checked(down);
  EXPECT_EQ(frame.result.occlusion_tested, 1);
  EXPECT_EQ(frame.result.occlusion_culled, 0);
  EXPECT_EQ(frame.pixels, reference.draw(down, {}, false).pixels) << "the skin should not show from inside";
  EXPECT_GT(covered_pixels(frame.pixels), 100000u);

  // Looking ahead from there, with brain behind and beside the eye: the near plane cuts the proxy, so
  // the brain is drawn without a query.
  const Camera ahead = camera({0.0f, -30.0f, top - 5.0f}, {0.0f, 100.0f, top - 40.0f}, 1.0f);
  const Frame near = target.draw_checked(ahead);
  EXPECT_EQ(near.result.occlusion_tested, 0);
  EXPECT_GT(covered_pixels(near.pixels), 10000u);
}

TEST(OcclusionCulling, ADentThroughTheSkinShowsTheBrain) {
  const Scene scene = default_scene_with(true);
  Scene skin_alone = default_scene_with(true);
  skin_alone.objects[brain].material.visible = false;
  SceneTarget target(scene), reference(skin_alone);
  const glm::vec3 direction(0.1f, -0.6f, 1.0f);
  const Camera view = outside(scene, direction);
  // 30 mm deep where the skin is about 10 mm over the brain, as wide as the skin's sigma.
  const ObjectDent deep[] = {{skin, {skin_point_toward(scene, direction), 30.0f, 14.0f}}};
  const Frame frame = target.draw_checked(view, deep);
  EXPECT_EQ(frame.result.occlusion_tested, 1);
  EXPECT_EQ(frame.result.occlusion_culled, 0);
  const std::size_t brain_pixels = differing_pixels(frame.pixels, reference.draw(view, deep, false).pixels);
  std::printf("the brain shows on %zu pixels through the dent\n", brain_pixels);
  EXPECT_GT(brain_pixels, 500u);

  // A shallow dent leaves it hidden, and culled.
  const ObjectDent shallow[] = {{skin, {skin_point_toward(scene, direction), 4.0f, 14.0f}}};
  EXPECT_EQ(target.draw_checked(view, shallow).result.occlusion_culled, 1);
}

// The pad: a dent of negative depth pushes the brain out through the skin, beyond the hull of its
// undeformed vertices. Its proxy grows by the depth, so the query still sees it.
TEST(OcclusionCulling, ABrainPushedOutThroughTheSkinIsDrawn) {
  const Scene scene = default_scene_with(true);
  SceneTarget target(scene);
  const glm::vec3 direction(0.15f, -1.0f, 0.35f);
  const auto& positions = scene.objects[brain].mesh.positions_mm;
  const glm::vec3 bulge = *std::max_element(
      positions.begin(), positions.end(),
      [&](glm::vec3 a, glm::vec3 b) { return glm::dot(a, direction) < glm::dot(b, direction); });
  const ObjectDent out[] = {{brain, {bulge, -25.0f, 8.0f}}};
  const Frame frame = target.draw_checked(outside(scene, direction), out);
  EXPECT_EQ(frame.result.occlusion_tested, 1);
  EXPECT_EQ(frame.result.occlusion_culled, 0);
  const ObjectDent in[] = {{brain, {bulge, 4.0f, 5.0f}}};
  EXPECT_EQ(target.draw_checked(outside(scene, direction), in).result.occlusion_culled, 1);
}

// A ball through a wall drawn before it: its front cap shows, the rest is behind the wall, including
// its whole silhouette. A query that drew the proxy's back faces (or a proxy turned inside out) would
// cull it.
TEST(OcclusionCulling, AnObjectPiercingTheOneInFrontIsDrawn) {
  Scene scene;
  SceneObject wall;
  wall.name = "wall";
  wall.mesh = make_box({300.0f, 10.0f, 300.0f});  // y from -5 to 5
  SceneObject ball;
  ball.name = "ball";
  ball.mesh = make_sphere(30.0f, 4000);
  ball.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 15.0f, 0.0f));  // 10 mm out in front
  scene.objects = {wall, ball};
  const Camera view = camera({0.0f, -200.0f, 20.0f}, {0, 0, 0}, 5.0f);
  SceneTarget target(scene);
  const Frame frame = target.draw_checked(view);
  EXPECT_EQ(frame.result.occlusion_tested, 1);
  EXPECT_EQ(frame.result.occlusion_culled, 0);
  scene.objects[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 40.0f, 0.0f));  // all behind
  SceneTarget hidden(scene);
  EXPECT_EQ(hidden.draw_checked(view).result.occlusion_culled, 1);
}

}  // namespace
}  // namespace palpate::gl
