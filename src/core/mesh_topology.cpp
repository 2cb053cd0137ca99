#include "palpate/core/mesh_topology.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace palpate {
namespace {

struct DirectedEdge {
  std::uint32_t lo, hi;
  bool forward;  // traversed lo -> hi
  bool operator<(const DirectedEdge& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
};

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

MeshTopology analyze_topology(const Mesh& mesh) {
  MeshTopology topo;
  const std::size_t triangles = mesh.triangle_count();
  std::vector<DirectedEdge> edges;
  edges.reserve(triangles * 3);
  std::vector<std::uint32_t> parent(mesh.vertex_count());
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<bool> referenced(mesh.vertex_count(), false);

  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t v[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) ++topo.degenerate_triangles;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      referenced[a] = true;
      parent[find_root(parent, a)] = find_root(parent, b);
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b), a < b});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int forward = 0;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) {
      forward += edges[j].forward ? 1 : 0;
      ++j;
    }
    const std::size_t uses = j - i;
    ++topo.edges;
    if (uses == 1) ++topo.boundary_edges;
    if (uses > 2) ++topo.nonmanifold_edges;
    if (uses == 2 && forward != 1) ++topo.misoriented_edges;
    i = j;
  }
  std::size_t used = 0;
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!referenced[v]) {
      ++topo.unreferenced_vertices;
      continue;
    }
    ++used;
    if (find_root(parent, v) == v) ++topo.components;
  }
  topo.euler_characteristic =
      static_cast<long>(used) - static_cast<long>(topo.edges) + static_cast<long>(triangles);
  return topo;
}

}  // namespace palpate
