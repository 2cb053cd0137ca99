#include "palpate/core/displacement.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <numeric>
#include <unordered_map>

namespace palpate {
namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

struct CellHash {
  std::size_t operator()(const glm::ivec3& c) const noexcept {
    return std::size_t(c.x) * 73856093u ^ std::size_t(c.y) * 19349663u ^ std::size_t(c.z) * 83492791u;
  }
};

}  // namespace

float default_weld_tolerance_mm(const Mesh& mesh) noexcept {
  return std::max(1e-5f, 1e-6f * glm::length(bounds(mesh).size_mm()));
}

PositionGroups group_positions(const Mesh& mesh, float tolerance_mm) {
  const std::size_t n = mesh.positions_mm.size();
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  // Cells as wide as the tolerance: vertices within it lie in the same or a neighbouring cell.
  const float cell = std::max(tolerance_mm, 1e-12f);
  std::unordered_map<glm::ivec3, std::vector<std::uint32_t>, CellHash> grid;
  grid.reserve(n);
  const float tolerance2 = tolerance_mm * tolerance_mm;
  for (std::uint32_t v = 0; v < n; ++v) {
    const glm::vec3 p = mesh.positions_mm[v];
    const glm::ivec3 c(glm::floor(p / cell));
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = grid.find(c + glm::ivec3(dx, dy, dz));
          if (it == grid.end()) continue;
          for (const std::uint32_t w : it->second) {
            const glm::vec3 d = mesh.positions_mm[w] - p;
            if (glm::dot(d, d) <= tolerance2) parent[find_root(parent, v)] = find_root(parent, w);
          }
        }
    grid[c].push_back(v);
  }
  PositionGroups groups;
  groups.group.resize(n);
  std::vector<std::uint32_t> number(n, std::uint32_t(-1));
  for (std::uint32_t v = 0; v < n; ++v) {
    const std::uint32_t root = find_root(parent, v);
    if (number[root] == std::uint32_t(-1)) number[root] = std::uint32_t(groups.count++);
    groups.group[v] = number[root];
  }
  return groups;
}

void compute_displacement_directions(Mesh& mesh, float weld_tolerance_mm) {
  const PositionGroups groups = group_positions(mesh, weld_tolerance_mm);
  if (groups.count == mesh.positions_mm.size()) {
    mesh.directions.clear();
    return;
  }
  std::vector<glm::vec3> sums(groups.count, glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    // The cross product's length is twice the area: summing it weights each face by area.
    const glm::vec3 face =
        glm::cross(mesh.positions_mm[b] - mesh.positions_mm[a], mesh.positions_mm[c] - mesh.positions_mm[a]);
    for (const std::uint32_t v : {a, b, c}) sums[groups.group[v]] += face;
  }
  mesh.directions.resize(mesh.positions_mm.size());
  for (std::size_t v = 0; v < mesh.positions_mm.size(); ++v) {
    const glm::vec3 sum = sums[groups.group[v]];
    const float length = glm::length(sum);
    mesh.directions[v] = length > 0.0f ? sum / length : mesh.normals[v];
  }
}

Mesh weld_by_position(const Mesh& mesh, float tolerance_mm) {
  return weld_by_position(mesh, group_positions(mesh, tolerance_mm));
}

Mesh weld_by_position(const Mesh& mesh, const PositionGroups& groups) {
  Mesh welded;
  welded.positions_mm.resize(groups.count);
  for (std::size_t v = 0; v < mesh.positions_mm.size(); ++v)
    welded.positions_mm[groups.group[v]] = mesh.positions_mm[v];
  welded.indices.reserve(mesh.indices.size());
  for (const std::uint32_t i : mesh.indices) welded.indices.push_back(groups.group[i]);
  compute_vertex_normals(welded);
  return welded;
}

}  // namespace palpate
