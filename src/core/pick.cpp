#include "palpate/core/pick.hpp"

#include <glm/geometric.hpp>

namespace palpate {

BvhHit pick(const Bvh& bvh, const OrbitCamera& camera, glm::vec2 pixel_px, glm::vec2 viewport_px,
            ObjectMask seen) noexcept {
  const OrbitCamera::Ray ray = camera.ray_through(pixel_px, viewport_px);
  const Bounds box = bvh.bounds();
  const float reach = glm::distance(ray.origin_mm, box.center_mm()) + glm::length(box.size_mm()) + 1.0f;
  return bvh.first_hit(glm::dvec3(ray.origin_mm), glm::dvec3(ray.origin_mm + ray.direction * reach),
                       Faces::front, 0.0, seen);
}

}  // namespace palpate
