#include "mesh_reference.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace palpate::cli {
namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closest_point(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

MeshReference::MeshReference(const Scene& scene, float depth_cap_mm) : cap_(depth_cap_mm) {
  for (const SceneObject& object : scene.objects) grids_.push_back(build(object));
}

MeshReference::Grid MeshReference::build(const SceneObject& object) {
  Grid grid;
  const Mesh& mesh = object.mesh;
  glm::dvec3 lo(1e300), hi(-1e300);
  double edge_sum = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto world = [&](std::size_t corner) {
      return glm::dvec3(object.transform * glm::vec4(mesh.positions[mesh.indices[3 * t + corner]], 1.0f));
    };
    const Triangle tri{world(0), world(1), world(2)};
    lo = glm::min(lo, glm::min(tri.a, glm::min(tri.b, tri.c)));
    hi = glm::max(hi, glm::max(tri.a, glm::max(tri.b, tri.c)));
    edge_sum += glm::length(tri.b - tri.a);
    grid.triangles.push_back(tri);
  }
  // Cells about three edges wide: a few tens of triangles each where the surface passes.
  grid.cell = std::max(3.0 * edge_sum / double(std::max<std::size_t>(grid.triangles.size(), 1)), 1e-3);
  grid.origin = lo - grid.cell;
  grid.size = glm::ivec3(glm::floor((hi - grid.origin) / grid.cell)) + 2;
  const std::size_t cells = std::size_t(grid.size.x) * std::size_t(grid.size.y) * std::size_t(grid.size.z);
  const auto cell_range = [&](const Triangle& tri, glm::ivec3& first, glm::ivec3& last) {
    first = glm::ivec3(glm::floor((glm::min(tri.a, glm::min(tri.b, tri.c)) - grid.origin) / grid.cell));
    last = glm::ivec3(glm::floor((glm::max(tri.a, glm::max(tri.b, tri.c)) - grid.origin) / grid.cell));
  };
  const auto index = [&](int x, int y, int z) {
    return (std::size_t(z) * std::size_t(grid.size.y) + std::size_t(y)) * std::size_t(grid.size.x) +
           std::size_t(x);
  };
  // Two passes: count per cell, then fill.
  grid.offsets.assign(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> cursor;
    if (pass == 1) {
      for (std::size_t i = 0; i < cells; ++i) grid.offsets[i + 1] += grid.offsets[i];
      grid.entries.resize(grid.offsets[cells]);
      cursor.assign(grid.offsets.begin(), grid.offsets.end() - 1);
    }
    for (std::uint32_t t = 0; t < grid.triangles.size(); ++t) {
      glm::ivec3 first, last;
      cell_range(grid.triangles[t], first, last);
      for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
          for (int x = first.x; x <= last.x; ++x) {
            if (pass == 0)
              ++grid.offsets[index(x, y, z) + 1];
            else
              grid.entries[cursor[index(x, y, z)]++] = t;
          }
    }
  }
  return grid;
}

bool MeshReference::inside(const Grid& grid, glm::dvec3 p) const {
  const glm::ivec3 cell = glm::ivec3(glm::floor((p - grid.origin) / grid.cell));
  if (glm::any(glm::lessThan(cell, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(cell, grid.size)))
    return false;
  int crossings = 0;
  for (int z = cell.z; z < grid.size.z; ++z) {
    const std::size_t i =
        (std::size_t(z) * std::size_t(grid.size.y) + std::size_t(cell.y)) * std::size_t(grid.size.x) +
        std::size_t(cell.x);
    for (std::uint32_t e = grid.offsets[i]; e < grid.offsets[i + 1]; ++e) {
      const Triangle& tri = grid.triangles[grid.entries[e]];
      // Does the vertical line through p cross the triangle's xy projection? Barycentrics in 2D.
      const glm::dvec2 a(tri.a), b(tri.b), c(tri.c), q(p);
      const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (area == 0.0) continue;  // seen edge-on: no crossing of its interior
      const double u = ((b.x - q.x) * (c.y - q.y) - (c.x - q.x) * (b.y - q.y)) / area;
      const double v = ((c.x - q.x) * (a.y - q.y) - (a.x - q.x) * (c.y - q.y)) / area;
      const double w = 1.0 - u - v;
      if (u < 0.0 || v < 0.0 || w < 0.0) continue;
      const double crossing_z = u * tri.a.z + v * tri.b.z + w * tri.c.z;
      // Count each crossing once: in the cell that holds it, and only above p.
      const int crossing_cell = int(std::floor((crossing_z - grid.origin.z) / grid.cell));
      if (crossing_z > p.z && crossing_cell == z) ++crossings;
    }
  }
  return crossings % 2 == 1;
}

double MeshReference::distance(const Grid& grid, glm::dvec3 p) const {
  const glm::ivec3 centre = glm::ivec3(glm::floor((p - grid.origin) / grid.cell));
  double best = cap_;
  const int max_ring = int(std::ceil(cap_ / grid.cell)) + 1;
  for (int ring = 0; ring <= max_ring; ++ring) {
    // Cells of ring r+1 are at least r cells away from any point of the centre cell.
    if (best <= (ring - 1) * grid.cell) break;
    for (int z = centre.z - ring; z <= centre.z + ring; ++z)
      for (int y = centre.y - ring; y <= centre.y + ring; ++y)
        for (int x = centre.x - ring; x <= centre.x + ring; ++x) {
          const int chebyshev =
              std::max({std::abs(x - centre.x), std::abs(y - centre.y), std::abs(z - centre.z)});
          if (chebyshev != ring) continue;
          if (x < 0 || y < 0 || z < 0 || x >= grid.size.x || y >= grid.size.y || z >= grid.size.z) continue;
          const std::size_t i =
              (std::size_t(z) * std::size_t(grid.size.y) + std::size_t(y)) * std::size_t(grid.size.x) +
              std::size_t(x);
          for (std::uint32_t e = grid.offsets[i]; e < grid.offsets[i + 1]; ++e) {
            const Triangle& tri = grid.triangles[grid.entries[e]];
            best = std::min(best, glm::length(p - closest_point(p, tri.a, tri.b, tri.c)));
          }
        }
  }
  return best;
}

double MeshReference::depth_mm(glm::vec3 point) const {
  const glm::dvec3 p(point);
  double deepest = -cap_;
  bool in_any = false;
  for (const Grid& grid : grids_) {
    const double d = distance(grid, p);
    if (inside(grid, p)) {
      deepest = in_any ? std::max(deepest, d) : d;
      in_any = true;
    } else if (!in_any) {
      deepest = std::max(deepest, -d);
    }
  }
  return deepest;
}

}  // namespace palpate::cli
