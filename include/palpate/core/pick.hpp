#pragma once
// Picking: what the camera sees through a pixel of the application's real viewport.
#include <glm/vec2.hpp>

#include "palpate/core/bvh.hpp"
#include "palpate/core/orbit_camera.hpp"

namespace palpate {

// The first front face that the ray from the eye through `pixel_px` (counted from the top-left, in
// [0, viewport_px)) meets on the objects `seen` names (empty: all the tree holds), or no hit. The ray
// reaches past the far side of the tree. noexcept, no allocation.
BvhHit pick(const Bvh& bvh, const OrbitCamera& camera, glm::vec2 pixel_px, glm::vec2 viewport_px,
            ObjectMask seen = {}) noexcept;

}  // namespace palpate
