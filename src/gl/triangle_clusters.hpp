#pragma once
// Spatial clusters of a mesh's triangles, so that the renderer can hand the triangles that no dent
// reaches to the plain shader: beyond 4 sigma the deformation is exactly zero (deform.hpp's cutoff),
// so those triangles look the same either way and skip the per-vertex and per-fragment dent work.
// Written here because it is a Morton sort and a loop: no library would do less.
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "palpate/core/mesh.hpp"

namespace palpate::gl {

struct TriangleCluster {
  std::uint32_t first_index = 0;  // into the reordered index buffer
  std::uint32_t index_count = 0;
  glm::vec3 center{0.0f};  // bounding sphere of the cluster's vertices, object frame (mm)
  float radius = 0.0f;
};

// Reorders the triangles of `indices` (three per triangle) along a Morton curve of their centroids and
// cuts them into clusters of at most `triangles_per_cluster`; `moved_to`, if given, receives each
// triangle's new place (moved_to[old] = new). Allocates.
std::vector<TriangleCluster> cluster_triangles(std::vector<std::uint32_t>& indices,
                                               std::span<const glm::vec3> positions,
                                               std::size_t triangles_per_cluster,
                                               std::vector<std::uint32_t>* moved_to = nullptr);

// Renumbers the vertices in the order the triangles first use them (positions, normals and colours
// move along), so that the vertices of neighbouring triangles sit together in the vertex buffer: fewer
// cache misses when the vertex stage fetches and reuses them. Allocates.
void order_vertices_by_first_use(Mesh& mesh);

}  // namespace palpate::gl
