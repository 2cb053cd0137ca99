#pragma once
// An indexed triangle mesh in millimetres: the one geometry type of palpate.
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace palpate {

struct Mesh {
  std::vector<glm::vec3> positions_mm;
  std::vector<glm::vec3> normals;  // unit, one per position (outward)
  std::vector<glm::vec3> colors;   // linear RGB in [0,1], one per position, or empty
  // Where a dent moves each vertex: unit, one per position, shared by all vertices at one place (see
  // palpate/core/displacement.hpp); empty where no two vertices share a position: then the normals.
  std::vector<glm::vec3> directions;
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside

  std::size_t vertex_count() const noexcept { return positions_mm.size(); }
  std::size_t triangle_count() const noexcept { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 min_mm{0.0f};
  glm::vec3 max_mm{0.0f};
  glm::vec3 size_mm() const noexcept { return max_mm - min_mm; }
  glm::vec3 center_mm() const noexcept { return (min_mm + max_mm) * 0.5f; }
};

// Axis-aligned bounds of the positions; all zero for an empty mesh.
Bounds bounds(const Mesh& mesh) noexcept;

// Area-weighted vertex normals from the triangles (replaces mesh.normals; allocates).
void compute_vertex_normals(Mesh& mesh);

// Appends `part` to `into`, offsetting its indices. Colors are kept when either side has them
// (the side without gets `fill_color`).
void append_mesh(Mesh& into, const Mesh& part, glm::vec3 fill_color = glm::vec3(0.8f));

// Throws palpate::Error naming `what` when the mesh is inconsistent: indices out of range,
// a count not a multiple of 3, normals or colors of the wrong size, or non-finite values.
void validate_mesh(const Mesh& mesh, const std::string& what);

}  // namespace palpate
