#include "palpate/core/orbit_camera.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace palpate {
namespace {

glm::vec3 project(const OrbitCamera& camera, glm::vec3 p, float aspect) {
  const glm::vec4 clip = camera.projection(aspect) * camera.view() * glm::vec4(p, 1.0f);
  return glm::vec3(clip) / clip.w;
}

TEST(OrbitCamera, TargetProjectsToTheCentreAndUpIsUp) {
  OrbitCamera camera;
  camera.target_mm = {10, 20, 30};
  camera.yaw_rad = 0.7f;
  const glm::vec3 centre = project(camera, camera.target_mm, 1.25f);
  EXPECT_NEAR(centre.x, 0.0f, 1e-5f);
  EXPECT_NEAR(centre.y, 0.0f, 1e-5f);
  EXPECT_GT(project(camera, camera.target_mm + glm::vec3(0, 0, 10), 1.25f).y, 0.0f);
  EXPECT_NEAR(glm::distance(camera.eye(), camera.target_mm), camera.distance_mm, 1e-3f);
}

TEST(OrbitCamera, RayThroughAPixelHitsWhatProjectsThere) {
  OrbitCamera camera;
  camera.yaw_rad = -0.4f;
  camera.pitch_rad = 0.5f;
  const glm::vec2 size{640, 480};
  const glm::vec3 point{12, -7, 25};
  const glm::vec3 ndc = project(camera, point, size.x / size.y);
  const glm::vec2 pixel{(ndc.x + 1) * 0.5f * size.x - 0.5f, (1 - ndc.y) * 0.5f * size.y - 0.5f};
  const OrbitCamera::Ray ray = camera.ray_through(pixel, size);
  const glm::vec3 to_point = point - ray.origin_mm;
  const glm::vec3 closest = ray.origin_mm + ray.direction * glm::dot(to_point, ray.direction);
  EXPECT_NEAR(glm::distance(closest, point), 0.0f, 1e-2f);
}

TEST(OrbitCamera, PitchStaysOffThePolesAndFramingSeesTheBox) {
  OrbitCamera camera;
  camera.orbit(0.0f, 10.0f);
  EXPECT_LT(camera.pitch_rad, 1.5708f);
  const Bounds box{{-80, -100, -60}, {80, 100, 60}};
  const OrbitCamera framed = frame_bounds(box, 0.3f, 0.2f);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner{i & 1 ? box.max_mm.x : box.min_mm.x, i & 2 ? box.max_mm.y : box.min_mm.y,
                           i & 4 ? box.max_mm.z : box.min_mm.z};
    const glm::vec3 ndc = project(framed, corner, 1.0f);
    EXPECT_LE(std::abs(ndc.x), 1.0f);
    EXPECT_LE(std::abs(ndc.y), 1.0f);
    EXPECT_LT(ndc.z, 1.0f);
  }
}

}  // namespace
}  // namespace palpate
