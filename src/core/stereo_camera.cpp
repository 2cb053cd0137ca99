#include "palpate/core/stereo_camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace palpate {

MonoCamera mono_camera(const OrbitCamera& camera, float aspect) noexcept {
  // The same planes as OrbitCamera::projection.
  return {camera.view(), camera.fov_y_rad, aspect, std::max(0.1f, camera.distance_mm * 0.05f),
          camera.distance_mm * 20.0f};
}

EyeView StereoCamera::eye(Eye which, const MonoCamera& mono) const noexcept {
  const float side = which == Eye::left ? -0.5f : which == Eye::right ? 0.5f : 0.0f;
  glm::vec3 at = head_mm + glm::vec3(side * eye_separation_mm, 0.0f, 0.0f);
  const float convergence = std::max(convergence_mm, 1e-3f);
  at.z = std::max(at.z, -0.99f * convergence);  // in front of the screen
  // The screen: centred on the camera axis at z = -convergence, as high as the field of view there.
  const float half_height = convergence * std::tan(0.5f * mono.fov_y_rad);
  const float half_width = mono.aspect * half_height;
  const float to_screen = convergence + at.z;  // the eye's distance to the screen's plane
  const float scale = mono.near_mm / to_screen;
  EyeView view;
  view.projection =
      glm::frustum((-half_width - at.x) * scale, (half_width - at.x) * scale, (-half_height - at.y) * scale,
                   (half_height - at.y) * scale, mono.near_mm, mono.far_mm);
  view.view = glm::translate(glm::mat4(1.0f), -at) * mono.view;
  view.position_mm = glm::vec3(glm::inverse(mono.view) * glm::vec4(at, 1.0f));
  return view;
}

float StereoCamera::screen_parallax_mm(float depth_mm) const noexcept {
  return eye_separation_mm * (1.0f - convergence_mm / depth_mm);
}

}  // namespace palpate
