#pragma once
// A scene: named objects, each a mesh in its own frame, a rigid transform to world and a material.
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

#include "palpate/core/material.hpp"
#include "palpate/core/mesh.hpp"

namespace palpate {

struct SceneObject {
  std::string name;
  Mesh mesh;                  // object frame, mm
  glm::mat4 transform{1.0f};  // rigid: object frame to world (rotation + translation)
  Material material;
  std::filesystem::path source;  // where the mesh came from, if from a file
};

struct Scene {
  std::vector<SceneObject> objects;

  std::size_t vertex_count() const noexcept;
  std::size_t triangle_count() const noexcept;
};

// World-space bounds of one object, and of all objects (visible or not).
Bounds world_bounds(const SceneObject& object) noexcept;
Bounds world_bounds(const Scene& scene) noexcept;

}  // namespace palpate
