#pragma once
// A camera that orbits a target point: what the viewer drives with the mouse, and what the demo and
// benchmarks use to frame a scene. Right-handed, y up in view space; angles in radians.
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "palpate/core/mesh.hpp"

namespace palpate {

struct OrbitCamera {
  glm::vec3 target_mm{0.0f};   // world point looked at, mm
  float yaw_rad = 0.0f;        // about world +z, 0 looks along +y (from the front of the head)
  float pitch_rad = 0.2f;      // elevation above the xy plane, clamped to (-pi/2, pi/2)
  float distance_mm = 400.0f;  // from the target
  float fov_y_rad = 0.7f;      // vertical field of view

  glm::vec3 eye() const noexcept;
  glm::mat4 view() const noexcept;
  glm::mat4 projection(float aspect) const noexcept;  // near/far from the distance

  // Rotates by mouse drag (radians), keeping the pitch inside the poles.
  void orbit(float delta_yaw, float delta_pitch) noexcept;
  // Multiplies the distance by `factor` (> 0), within [1 mm, 1e6 mm].
  void zoom(float factor) noexcept;

  // A world-space ray through a pixel of a viewport of `viewport_size` pixels; `pixel` counts from the
  // top-left, in [0, viewport_size).
  struct Ray {
    glm::vec3 origin_mm, direction;  // direction unit length
  };
  Ray ray_through(glm::vec2 pixel, glm::vec2 viewport_size) const noexcept;
};

// A camera that sees the whole box from the given direction with a small margin.
OrbitCamera frame_bounds(const Bounds& box, float yaw_rad, float pitch_rad, float fov_y_rad = 0.7f) noexcept;

}  // namespace palpate
