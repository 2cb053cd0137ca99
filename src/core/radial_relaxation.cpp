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

namespace {

// True when a corner of the triangle is sharper than about 12 degrees.
bool has_sharp_corner(const Mesh& mesh, std::size_t t) {
  constexpr double cos2_limit = 0.978 * 0.978;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 p(mesh.positions_mm[mesh.indices[t + k]]);
    const glm::dvec3 a = glm::dvec3(mesh.positions_mm[mesh.indices[t + (k + 1) % 3]]) - p;
    const glm::dvec3 b = glm::dvec3(mesh.positions_mm[mesh.indices[t + (k + 2) % 3]]) - p;
    const double d = glm::dot(a, b);
    if (d > 0.0 && d * d > cos2_limit * glm::dot(a, a) * glm::dot(b, b)) return true;
  }
  return false;
}

// The centre each vertex is drawn to: the mean of its neighbours, or (area_weighted) the area-weighted
// mean of its triangles' centroids, which pays little heed to tiny triangles and so pulls apart two
// vertices crowding each other.
std::vector<glm::dvec3> targets(const Mesh& mesh, const Neighbours& n, const std::vector<char>& selected,
                                bool area_weighted) {
  std::vector<glm::dvec3> target(mesh.vertex_count(), glm::dvec3(0.0));
  if (!area_weighted) {
    for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
      if (!selected[v]) continue;
      for (std::uint32_t i = n.start[v]; i < n.start[v + 1]; ++i)
        target[v] += glm::dvec3(mesh.positions_mm[n.list[i]]);
      target[v] /= double(n.start[v + 1] - n.start[v]);
    }
    return target;
  }
  std::vector<double> weight(mesh.vertex_count(), 0.0);
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (!(selected[a] || selected[b] || selected[c])) continue;
    const glm::dvec3 pa(mesh.positions_mm[a]), pb(mesh.positions_mm[b]), pc(mesh.positions_mm[c]);
    const double area = glm::length(glm::cross(pb - pa, pc - pa));
    const glm::dvec3 centroid = (pa + pb + pc) / 3.0;
    for (std::uint32_t v : {a, b, c}) target[v] += area * centroid, weight[v] += area;
  }
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    if (selected[v]) target[v] = weight[v] > 0.0 ? target[v] / weight[v] : glm::dvec3(mesh.positions_mm[v]);
  }
  return target;
}

// Moves each selected vertex halfway toward its target within the tangent plane, then back onto the
// surface along its ray, and undoes the moves around any triangle that turned over.
void smooth(Mesh& mesh, glm::dvec3 centre, const RadialFunction& radius, const std::vector<char>& selected,
            bool area_weighted) {
  compute_vertex_normals(mesh);
  const std::vector<glm::dvec3> target = targets(mesh, neighbours(mesh), selected, area_weighted);
  const std::vector<glm::vec3> previous = mesh.positions_mm;
  std::vector<char> moved(mesh.vertex_count(), 0);
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!selected[v]) continue;
    const glm::dvec3 p(previous[v]), mean = target[v];
    const glm::dvec3 normal(mesh.normals[v]);
    const glm::dvec3 move = 0.5 * (mean - p - glm::dot(mean - p, normal) * normal);
    const glm::dvec3 w = glm::normalize(p + move - centre);
    mesh.positions_mm[v] = glm::vec3(centre + radius(w) * w);
    moved[v] = 1;
  }
  // Until no triangle is turned over (at worst every move is undone).
  std::vector<std::uint32_t> undo;
  do {
    undo.clear();
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
      if ((moved[a] | moved[b] | moved[c]) == 0 ||
          faces_away(glm::dvec3(mesh.positions_mm[a]) - centre, glm::dvec3(mesh.positions_mm[b]) - centre,
                     glm::dvec3(mesh.positions_mm[c]) - centre)) {
        continue;
      }
      for (std::uint32_t v : {a, b, c}) {
        if (moved[v]) undo.push_back(v);
      }
    }
    for (std::uint32_t v : undo) {
      mesh.positions_mm[v] = previous[v];
      moved[v] = 0;
    }
  } while (!undo.empty());
}

}  // namespace

void relax_radial_mesh(Mesh& mesh, glm::dvec3 centre, const RadialFunction& radius, int iterations,
                       double max_fold_rad) {
  std::vector<std::uint32_t> opposite = opposite_corners(mesh);
  const std::vector<char> all(mesh.vertex_count(), 1);
  for (int round = 0; round < iterations; ++round) {
    flip_toward_delaunay(mesh, opposite, centre, max_fold_rad);
    smooth(mesh, centre, radius, all, false);
  }
  // A few more rounds on the sharpest triangles only: cheap, and they lift the worst angles.
  std::vector<char> sharp(mesh.vertex_count());
  for (int round = 0; round < 3; ++round) {
    flip_toward_delaunay(mesh, opposite, centre, max_fold_rad);
    std::fill(sharp.begin(), sharp.end(), 0);
    bool any = false;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      if (!has_sharp_corner(mesh, t)) continue;
      for (int k = 0; k < 3; ++k) sharp[mesh.indices[t + k]] = 1;
      any = true;
    }
    if (!any) break;
    smooth(mesh, centre, radius, sharp, true);
  }
  flip_toward_delaunay(mesh, opposite, centre, max_fold_rad);
}

}  // namespace palpate::detail
