#include "core/radial_relaxation.hpp"

#include <algorithm>
#include <cstdint>
#include <glm/geometric.hpp>
#include <vector>

#include "core/edge_flips.hpp"

namespace palpate::detail {
namespace {

// Each vertex's neighbours, in compressed rows: in a closed, consistently oriented mesh the vertex that
// follows v in each of v's triangles is each neighbour exactly once.
struct Neighbours {
  std::vector<std::uint32_t> start, list;
};

Neighbours neighbours(const Mesh& mesh) {
  Neighbours n;
  n.start.assign(mesh.vertex_count() + 1, 0);
  for (std::uint32_t v : mesh.indices) ++n.start[v + 1];
  for (std::size_t i = 1; i < n.start.size(); ++i) n.start[i] += n.start[i - 1];
  n.list.resize(mesh.indices.size());
  std::vector<std::uint32_t> fill(n.start.begin(), n.start.end() - 1);
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) n.list[fill[mesh.indices[t + k]]++] = mesh.indices[t + (k + 1) % 3];
  }
  return n;
}

bool faces_away(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const double volume = glm::dot(a, glm::cross(b, c));
  return volume > 0.0 && volume * volume > 1e-18 * glm::dot(a, a) * glm::dot(b, b) * glm::dot(c, c);
}

}  // namespace

void relax_radial_mesh(Mesh& mesh, glm::dvec3 centre, const RadialFunction& radius, int iterations,
                       double max_fold_rad) {
  std::vector<std::uint32_t> opposite = opposite_corners(mesh);
  std::vector<glm::vec3> previous;
  std::vector<char> moved(mesh.vertex_count());
  std::vector<std::uint32_t> undo;
  for (int round = 0; round < iterations; ++round) {
    flip_toward_delaunay(mesh, opposite, centre, max_fold_rad);
    compute_vertex_normals(mesh);
    const Neighbours n = neighbours(mesh);
    previous = mesh.positions;
    for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::dvec3 p(previous[v]);
      glm::dvec3 mean(0.0);
      for (std::uint32_t i = n.start[v]; i < n.start[v + 1]; ++i) mean += glm::dvec3(previous[n.list[i]]);
      mean /= double(n.start[v + 1] - n.start[v]);
      const glm::dvec3 normal(mesh.normals[v]);
      const glm::dvec3 move = 0.5 * (mean - p - glm::dot(mean - p, normal) * normal);
      const glm::dvec3 w = glm::normalize(p + move - centre);
      mesh.positions[v] = glm::vec3(centre + radius(w) * w);
      moved[v] = 1;
    }
    // Undo the moves around triangles that turned over, until none does (at worst every move is undone).
    do {
      undo.clear();
      for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        if ((moved[a] | moved[b] | moved[c]) == 0 ||
            faces_away(glm::dvec3(mesh.positions[a]) - centre, glm::dvec3(mesh.positions[b]) - centre,
                       glm::dvec3(mesh.positions[c]) - centre)) {
          continue;
        }
        for (std::uint32_t v : {a, b, c}) {
          if (moved[v]) undo.push_back(v);
        }
      }
      for (std::uint32_t v : undo) {
        mesh.positions[v] = previous[v];
        moved[v] = 0;
      }
    } while (!undo.empty());
  }
  flip_toward_delaunay(mesh, opposite, centre, max_fold_rad);
}

}  // namespace palpate::detail
