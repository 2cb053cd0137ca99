#include "palpate/haptics/device_transform.hpp"

#include <algorithm>
#include <cmath>
#include <glm/matrix.hpp>
#include <string>

#include "palpate/core/error.hpp"

namespace palpate {

DeviceTransform fit_workspace(const Bounds& device_workspace, const Bounds& scene_region) noexcept {
  const glm::vec3 device_size = device_workspace.size_mm(), scene_size = scene_region.size_mm();
  float scale = 1.0f;
  bool first = true;
  for (int axis = 0; axis < 3; ++axis) {
    if (device_size[axis] <= 0.0f) continue;
    const float ratio = scene_size[axis] / device_size[axis];
    scale = first ? ratio : std::min(scale, ratio);
    first = false;
  }
  if (!(scale > 0.0f)) scale = 1.0f;
  DeviceTransform transform;
  transform.scale = scale;
  transform.translation_mm = scene_region.center_mm() - scale * device_workspace.center_mm();
  return transform;
}

void validate_device_transform(const DeviceTransform& transform) {
  if (!(std::isfinite(transform.scale) && transform.scale > 0.0f)) {
    throw Error("device transform: scale must be positive and finite, got " +
                std::to_string(transform.scale));
  }
  const glm::mat3 gram = glm::transpose(transform.rotation) * transform.rotation;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const float expected = i == j ? 1.0f : 0.0f;
      if (!(std::abs(gram[i][j] - expected) <= 1e-4f)) {
        throw Error("device transform: rotation is not orthonormal (R^T R differs from I by " +
                    std::to_string(gram[i][j] - expected) + " at [" + std::to_string(i) + "][" +
                    std::to_string(j) + "])");
      }
    }
  }
  if (!(std::abs(glm::determinant(transform.rotation) - 1.0f) <= 1e-4f)) {
    throw Error("device transform: rotation must have determinant +1 (a mirror flips the surface normals)");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(transform.translation_mm[axis]))
      throw Error("device transform: translation is not finite");
  }
}

}  // namespace palpate
