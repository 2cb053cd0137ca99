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

Bounds world_bounds(const SceneObject& object) noexcept {
  Bounds b;
  for (std::size_t i = 0; i < object.mesh.positions_mm.size(); ++i) {
    const glm::vec3 w = glm::vec3(object.transform * glm::vec4(object.mesh.positions_mm[i], 1.0f));
    b = i == 0 ? Bounds{w, w} : Bounds{glm::min(b.min_mm, w), glm::max(b.max_mm, w)};
  }
  return b;
}

Bounds world_bounds(const Scene& scene) noexcept {
  Bounds b;
  bool first = true;
  for (const SceneObject& object : scene.objects) {
    if (object.mesh.positions_mm.empty()) continue;
    const Bounds o = world_bounds(object);
    b = first ? o : Bounds{glm::min(b.min_mm, o.min_mm), glm::max(b.max_mm, o.max_mm)};
    first = false;
  }
  return b;
}

}  // namespace palpate
