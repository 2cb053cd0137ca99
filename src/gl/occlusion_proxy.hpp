#pragma once
// The stand-in that an occlusion query draws for an object: a closed convex mesh of a few thousand
// triangles whatever the object's size, that contains the object even when its vertices have moved by
// up to `pad` mm (its dents), for any pad >= 0 chosen per frame, and hugs it closely enough that an
// object hidden inside another one is found hidden.
//
// First a discrete-orientation polytope: the object's vertices bounded in 262 directions (the six axes
// and 256 spread over the sphere), each plane moved out by the margin. Its faces stand at most a few
// percent of the object's radius off its convex hull (more at sharp edges, where the nearest
// directions are farther apart), and it never degenerates, flat meshes included.
// Then the dents: the Minkowski sum of that polytope with the cube [-pad, pad]^3. The cube contains the
// ball of radius pad, so each face moves out by at least pad (conservative; at most sqrt(3) pad along
// the cube's diagonals). The faces of such a sum are the same for every pad > 0, so it is computed
// once and each vertex is corner + pad * direction, with the direction a corner of the unit cube: the
// vertex shader pads it. (Scaling about the centre instead would move far faces out more than near ones,
// and a thin object's faces without bound.) Both hulls are qhull's.
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <vector>

namespace palpate::gl {

struct OcclusionProxy {
  std::vector<glm::vec3> corners;      // world mm: the polytope's vertices (pad 0)
  std::vector<glm::vec3> directions;   // each component -1 or +1
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside

  glm::vec3 vertex(std::size_t i, float pad_mm) const noexcept { return corners[i] + pad_mm * directions[i]; }
};

// The proxy of the points (world mm, all finite): it holds every point within margin_mm + pad of them.
// Nothing for no points, or should qhull fail (then the object cannot be culled). Allocates.
std::optional<OcclusionProxy> make_occlusion_proxy(std::span<const glm::vec3> world_positions,
                                                   float margin_mm);

}  // namespace palpate::gl
