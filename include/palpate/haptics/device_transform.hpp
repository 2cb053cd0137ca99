#pragma once
// From the device's frame to the scene: scene = rotation * (scale * device) + translation.
// `scale` is the workspace scaling (scene mm per device mm). Forces go back through the rotation only:
// a force is felt in newtons whatever the scaling, so the stiffness felt at the device is the
// material's k times `scale` (keep it under DeviceLimits::max_stiffness_n_per_mm).
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include "palpate/core/mesh.hpp"

namespace palpate {

struct DeviceTransform {
  float scale = 1.0f;              // scene mm per device mm, > 0
  glm::mat3 rotation{1.0f};        // device axes to scene axes, orthonormal with det +1
  glm::vec3 translation_mm{0.0f};  // scene position of the device origin, mm

  glm::vec3 point_to_scene(glm::vec3 device_mm) const noexcept {
    return rotation * (scale * device_mm) + translation_mm;
  }
  glm::vec3 velocity_to_scene(glm::vec3 device_mm_per_s) const noexcept {
    return rotation * (scale * device_mm_per_s);
  }
  glm::vec3 force_to_device(glm::vec3 scene_force_n) const noexcept {
    return glm::transpose(rotation) * scene_force_n;
  }
  // The inverse map, for aiming a scripted path at a scene point.
  glm::vec3 point_to_device(glm::vec3 scene_mm) const noexcept {
    return glm::transpose(rotation) * (scene_mm - translation_mm) / scale;
  }
  glm::vec3 direction_to_device(glm::vec3 scene_direction) const noexcept {
    return glm::transpose(rotation) * scene_direction;
  }
};

// Maps the box `device_workspace` (device mm) onto `scene_region` (scene mm), centre on centre, with
// the largest uniform scale that keeps the workspace inside the region, and no rotation.
DeviceTransform fit_workspace(const Bounds& device_workspace, const Bounds& scene_region) noexcept;

// Throws palpate::Error naming the field when the scale is not positive and finite or the rotation is
// not a proper rotation (within 1e-4).
void validate_device_transform(const DeviceTransform& transform);

}  // namespace palpate
