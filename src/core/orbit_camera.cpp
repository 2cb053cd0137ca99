#include "palpate/core/orbit_camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace palpate {

glm::vec3 OrbitCamera::eye() const noexcept {
  // yaw 0 puts the eye on +y looking back toward -y; +z is up.
  const glm::vec3 from_target{std::sin(yaw_rad) * std::cos(pitch_rad),
                              std::cos(yaw_rad) * std::cos(pitch_rad), std::sin(pitch_rad)};
  return target_mm + distance_mm * from_target;
}

glm::mat4 OrbitCamera::view() const noexcept {
  return glm::lookAt(eye(), target_mm, glm::vec3(0.0f, 0.0f, 1.0f));
}

glm::mat4 OrbitCamera::projection(float aspect) const noexcept {
  const float near_mm = std::max(0.1f, distance_mm * 0.05f);
  return glm::perspective(fov_y_rad, aspect, near_mm, distance_mm * 20.0f);
}

void OrbitCamera::orbit(float delta_yaw, float delta_pitch) noexcept {
  yaw_rad += delta_yaw;
  pitch_rad = std::clamp(pitch_rad + delta_pitch, -1.55f, 1.55f);
}

void OrbitCamera::zoom(float factor) noexcept {
  if (factor > 0.0f) distance_mm = std::clamp(distance_mm * factor, 1.0f, 1e6f);
}

OrbitCamera::Ray OrbitCamera::ray_through(glm::vec2 pixel, glm::vec2 viewport_size) const noexcept {
  const glm::vec2 ndc{2.0f * (pixel.x + 0.5f) / viewport_size.x - 1.0f,
                      1.0f - 2.0f * (pixel.y + 0.5f) / viewport_size.y};
  const glm::mat4 inverse = glm::inverse(projection(viewport_size.x / viewport_size.y) * view());
  const glm::vec4 near_point = inverse * glm::vec4(ndc, -1.0f, 1.0f);
  const glm::vec4 far_point = inverse * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 a = glm::vec3(near_point) / near_point.w, b = glm::vec3(far_point) / far_point.w;
  return {eye(), glm::normalize(b - a)};
}

OrbitCamera frame_bounds(const Bounds& box, float yaw_rad, float pitch_rad, float fov_y_rad) noexcept {
  OrbitCamera camera;
  camera.target_mm = box.center_mm();
  camera.yaw_rad = yaw_rad;
  camera.pitch_rad = pitch_rad;
  camera.fov_y_rad = fov_y_rad;
  const float radius = std::max(1.0f, 0.5f * glm::length(box.size_mm()));
  camera.distance_mm = radius / std::sin(fov_y_rad * 0.5f) * 1.05f;
  return camera;
}

}  // namespace palpate
