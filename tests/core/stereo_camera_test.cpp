// StereoCamera against the geometry of two eyes and one screen, worked out here by similar triangles.
#include "palpate/core/stereo_camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace palpate {
namespace {

glm::vec3 project(const EyeView& eye, glm::vec3 world) {
  const glm::vec4 clip = eye.projection * eye.view * glm::vec4(world, 1.0f);
  return glm::vec3(clip) / clip.w;
}

// A camera away from the origin and turned, so that a mix-up of frames shows.
OrbitCamera turned_camera() {
  OrbitCamera camera;
  camera.target_mm = {30.0f, -20.0f, 15.0f};
  camera.yaw_rad = 0.6f;
  camera.pitch_rad = 0.3f;
  camera.distance_mm = 450.0f;
  return camera;
}

// A point given in the mono camera's frame (x right, y up, -z ahead), in the world.
glm::vec3 world_of(const MonoCamera& mono, glm::vec3 in_camera) {
  return glm::vec3(glm::inverse(mono.view) * glm::vec4(in_camera, 1.0f));
}

TEST(StereoCamera, EveryEyeSeesTheSameScreenWhereverTheHeadIs) {
  const MonoCamera mono = mono_camera(turned_camera(), 1.6f);
  StereoCamera stereo;
  stereo.convergence_mm = 450.0f;
  const float half_height = 450.0f * std::tan(0.5f * mono.fov_y_rad), half_width = 1.6f * half_height;
  for (const glm::vec3 head :
       {glm::vec3(0.0f), glm::vec3(40.0f, -25.0f, 60.0f), glm::vec3(-80.0f, 10.0f, -100.0f)}) {
    stereo.head_mm = head;
    for (const Eye eye : {Eye::left, Eye::right, Eye::centre}) {
      const EyeView view = stereo.eye(eye, mono);
      for (const float sx : {-1.0f, 1.0f}) {
        for (const float sy : {-1.0f, 1.0f}) {
          const glm::vec3 corner =
              project(view, world_of(mono, {sx * half_width, sy * half_height, -450.0f}));
          EXPECT_NEAR(corner.x, sx, 1e-4f);
          EXPECT_NEAR(corner.y, sy, 1e-4f);
        }
      }
    }
  }
}

TEST(StereoCamera, ParallaxIsTheSimilarTrianglesOneAndNeverVertical) {
  const MonoCamera mono = mono_camera(turned_camera(), 1.25f);
  StereoCamera stereo;
  stereo.eye_separation_mm = 64.0f;
  stereo.convergence_mm = 450.0f;
  const float half_width = 1.25f * 450.0f * std::tan(0.5f * mono.fov_y_rad);
  const EyeView left = stereo.eye(Eye::left, mono), right = stereo.eye(Eye::right, mono);
  EXPECT_NEAR(glm::distance(left.position_mm, right.position_mm), 64.0f, 1e-3f);
  for (const float depth : {200.0f, 450.0f, 900.0f, 5000.0f}) {
    // The ray from an eye at x = +-32 to the point (0, 0, -depth) meets the screen (z = -450) at
    // x = +-32 (1 - 450 / depth).
    const float expected = 64.0f * (1.0f - 450.0f / depth);
    const glm::vec3 point = world_of(mono, {0.0f, 0.0f, -depth});
    const float parallax = (project(right, point).x - project(left, point).x) * half_width;
    EXPECT_NEAR(parallax, expected, 1e-3f) << "depth " << depth;
    EXPECT_NEAR(stereo.screen_parallax_mm(depth), expected, 1e-4f);
    // Off the axis the parallax is the same and only horizontal.
    const glm::vec3 off = world_of(mono, {70.0f, -45.0f, -depth});
    EXPECT_NEAR((project(right, off).x - project(left, off).x) * half_width, expected, 1e-3f);
    EXPECT_NEAR(project(right, off).y, project(left, off).y, 1e-5f);
  }
}

TEST(StereoCamera, ACentredEyeIsTheMonoCamera) {
  const OrbitCamera camera = turned_camera();
  const EyeView centre = StereoCamera{}.eye(Eye::centre, mono_camera(camera, 1.5f));
  const glm::mat4 mono = camera.projection(1.5f) * camera.view(), eye = centre.projection * centre.view;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(eye[c][r], mono[c][r], 1e-5f * std::max(1.0f, std::abs(mono[c][r])));
  EXPECT_NEAR(glm::distance(centre.position_mm, camera.eye()), 0.0f, 1e-3f);
}

TEST(StereoCamera, TheHeadMovesWhatLiesBehindTheScreenWithItAndNotTheScreen) {
  const MonoCamera mono = mono_camera(turned_camera(), 1.0f);
  StereoCamera stereo;
  stereo.convergence_mm = 450.0f;
  const float half_width = 450.0f * std::tan(0.5f * mono.fov_y_rad);
  const glm::vec3 on_screen = world_of(mono, {20.0f, 10.0f, -450.0f}),
                  behind = world_of(mono, {0.0f, 0.0f, -900.0f});
  const glm::vec3 screen_before = project(stereo.eye(Eye::centre, mono), on_screen);
  stereo.head_mm = {30.0f, 0.0f, 0.0f};
  const EyeView moved = stereo.eye(Eye::centre, mono);
  EXPECT_NEAR(project(moved, on_screen).x, screen_before.x, 1e-5f);
  EXPECT_NEAR(project(moved, on_screen).y, screen_before.y, 1e-5f);
  // From x = 30 the ray to (0, 0, -900) meets the screen at x = 30 (1 - 450 / 900) = 15 mm.
  EXPECT_NEAR(project(moved, behind).x * half_width, 15.0f, 1e-3f);
}

TEST(StereoCamera, AHeadThroughTheScreenStaysInFrontOfIt) {
  StereoCamera stereo;
  stereo.head_mm = {0.0f, 0.0f, -10000.0f};
  const EyeView eye = stereo.eye(Eye::right, mono_camera(turned_camera(), 1.0f));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(eye.projection[c][r]));
  EXPECT_GT(eye.projection[1][1], 0.0f);  // not turned upside down
}

}  // namespace
}  // namespace palpate
