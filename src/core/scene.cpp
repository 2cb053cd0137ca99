#include "palpate/core/scene.hpp"

#include <glm/common.hpp>

namespace palpate {

std::size_t Scene::vertex_count() const noexcept {
  std::size_t n = 0;
  for (const SceneObject& o : objects) n += o.mesh.vertex_count();
  return n;
}

std::size_t Scene::triangle_count() const noexcept {
  std::size_t n = 0;
  for (const SceneObject& o : objects) n += o.mesh.triangle_count();
  return n;
}

Bounds world_bounds(const Scene& scene) noexcept {
  bool first = true;
  Bounds b;
  for (const SceneObject& o : scene.objects) {
    for (const glm::vec3& p : o.mesh.positions) {
      const glm::vec3 w = glm::vec3(o.transform * glm::vec4(p, 1.0f));
      if (first) {
        b = {w, w};
        first = false;
      }
      b.min = glm::min(b.min, w);
      b.max = glm::max(b.max, w);
    }
  }
  return b;
}

}  // namespace palpate
