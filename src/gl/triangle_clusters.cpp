#include "triangle_clusters.hpp"

#include <algorithm>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <utility>

namespace palpate::gl {
namespace {

// Spreads the low 10 bits of v so that two zero bits follow each.
std::uint32_t spread_bits(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

}  // namespace

std::vector<TriangleCluster> cluster_triangles(std::vector<std::uint32_t>& indices,
                                               std::span<const glm::vec3> positions,
                                               std::size_t triangles_per_cluster,
                                               std::vector<std::uint32_t>* moved_to) {
  const std::size_t triangles = indices.size() / 3;
  if (triangles == 0 || positions.empty()) return {};
  glm::vec3 low = positions[0], high = positions[0];
  for (const glm::vec3& p : positions) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  const glm::vec3 scale = 1023.0f / glm::max(high - low, glm::vec3(1e-6f));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order(triangles);  // (Morton code, triangle)
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::vec3 centroid =
        (positions[indices[3 * t]] + positions[indices[3 * t + 1]] + positions[indices[3 * t + 2]]) / 3.0f;
    const glm::uvec3 cell =
        glm::uvec3(glm::clamp((centroid - low) * scale, glm::vec3(0.0f), glm::vec3(1023.0f)));
    order[t] = {spread_bits(cell.x) | (spread_bits(cell.y) << 1) | (spread_bits(cell.z) << 2),
                static_cast<std::uint32_t>(t)};
  }
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> sorted(indices.size());
  for (std::size_t t = 0; t < triangles; ++t) {
    std::copy_n(indices.begin() + 3 * static_cast<std::ptrdiff_t>(order[t].second), 3,
                sorted.begin() + 3 * t);
  }
  indices = std::move(sorted);
  if (moved_to) {
    moved_to->resize(triangles);
    for (std::size_t t = 0; t < triangles; ++t) (*moved_to)[order[t].second] = static_cast<std::uint32_t>(t);
  }

  std::vector<TriangleCluster> clusters;
  clusters.reserve(triangles / triangles_per_cluster + 1);
  for (std::size_t first = 0; first < triangles; first += triangles_per_cluster) {
    const std::size_t count = std::min(triangles_per_cluster, triangles - first);
    glm::vec3 box_low = positions[indices[3 * first]], box_high = box_low;
    for (std::size_t i = 3 * first; i < 3 * (first + count); ++i) {
      box_low = glm::min(box_low, positions[indices[i]]);
      box_high = glm::max(box_high, positions[indices[i]]);
    }
    TriangleCluster cluster;
    cluster.first_index = static_cast<std::uint32_t>(3 * first);
    cluster.index_count = static_cast<std::uint32_t>(3 * count);
    cluster.center = (box_low + box_high) * 0.5f;
    for (std::size_t i = 3 * first; i < 3 * (first + count); ++i) {
      cluster.radius = std::max(cluster.radius, glm::distance(cluster.center, positions[indices[i]]));
    }
    clusters.push_back(cluster);
  }
  return clusters;
}

void order_vertices_by_first_use(Mesh& mesh) {
  constexpr std::uint32_t unused = ~0u;
  std::vector<std::uint32_t> new_index(mesh.positions_mm.size(), unused);
  std::vector<std::uint32_t> old_index;
  old_index.reserve(mesh.positions_mm.size());
  for (std::uint32_t& index : mesh.indices) {
    if (new_index[index] == unused) {
      new_index[index] = static_cast<std::uint32_t>(old_index.size());
      old_index.push_back(index);
    }
    index = new_index[index];
  }
  for (std::uint32_t i = 0; i < mesh.positions_mm.size(); ++i) {  // vertices of no triangle go last
    if (new_index[i] == unused) old_index.push_back(i);
  }
  const auto reorder = [&](std::vector<glm::vec3>& values) {
    if (values.empty()) return;
    std::vector<glm::vec3> ordered(values.size());
    for (std::size_t i = 0; i < old_index.size(); ++i) ordered[i] = values[old_index[i]];
    values = std::move(ordered);
  };
  reorder(mesh.positions_mm);
  reorder(mesh.normals);
  reorder(mesh.colors);
  reorder(mesh.directions);
}

}  // namespace palpate::gl
