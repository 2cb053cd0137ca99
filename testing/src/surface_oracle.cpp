#include "palpate/testing/surface_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/testing/reference_geometry.hpp"

namespace palpate::testing {
namespace {

glm::dvec3 unit(const glm::dvec3& v, const glm::dvec3& fallback) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : fallback;
}

}  // namespace

MeshOracle::MeshOracle(const Scene& scene, double depth_cap_mm) : cap_(depth_cap_mm) {
  for (const SceneObject& object : scene.objects) {
    if (object.material.touchable && object.mesh.triangle_count() > 0) parts_.push_back(make_part(object));
  }
}

std::size_t MeshOracle::triangle_count() const noexcept {
  std::size_t n = 0;
  for (const Part& part : parts_) n += part.triangles.size();
  return n;
}

MeshOracle::Part MeshOracle::make_part(const SceneObject& object) {
  Part part;
  const Mesh& mesh = object.mesh;
  const bool has_normals = mesh.normals.size() == mesh.positions_mm.size();
  const glm::dmat3 rotation(glm::mat3(object.transform));
  const auto world = [&](std::uint32_t i) {
    return glm::dvec3(glm::vec3(object.transform * glm::vec4(mesh.positions_mm[i], 1.0f)));
  };
  glm::dvec3 lo(1e300), hi(-1e300);
  double edge_sum = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    Triangle tri{world(i0), world(i1), world(i2), {}, {}, {}, {}};
    tri.normal = glm::cross(tri.b - tri.a, tri.c - tri.a);
    const glm::dvec3 face = unit(tri.normal, glm::dvec3(0.0, 0.0, 1.0));
    const auto vertex_normal = [&](std::uint32_t i) {
      return has_normals ? unit(rotation * glm::dvec3(mesh.normals[i]), face) : face;
    };
    tri.na = vertex_normal(i0), tri.nb = vertex_normal(i1), tri.nc = vertex_normal(i2);
    for (const glm::dvec3& v : {tri.a, tri.b, tri.c}) lo = glm::min(lo, v), hi = glm::max(hi, v);
    edge_sum += glm::length(tri.b - tri.a);
    part.triangles.push_back(tri);
  }
  const auto count = part.triangles.size();

  // Projection grids, for the winding rays.
  const int cells = std::clamp(int(std::sqrt(double(count) / 2.0)), 1, 512);
  for (int axis = 0; axis < 3; ++axis) {
    ProjectionGrid& g = part.projections[axis];
    g.axis = axis;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    g.cells = cells;
    g.origin = {lo[u], lo[v]};
    g.cell = glm::max(glm::dvec2(hi[u] - lo[u], hi[v] - lo[v]) / double(cells), glm::dvec2(1e-9));
    g.bins.assign(std::size_t(cells * cells), {});
    const auto cell_of = [&](double x, double origin, double size) {
      return std::clamp(int(std::floor((x - origin) / size)), 0, cells - 1);
    };
    for (std::uint32_t i = 0; i < count; ++i) {
      const Triangle& t = part.triangles[i];
      const double u0 = std::min({t.a[u], t.b[u], t.c[u]}), u1 = std::max({t.a[u], t.b[u], t.c[u]});
      const double v0 = std::min({t.a[v], t.b[v], t.c[v]}), v1 = std::max({t.a[v], t.b[v], t.c[v]});
      for (int j = cell_of(v0, g.origin.y, g.cell.y); j <= cell_of(v1, g.origin.y, g.cell.y); ++j) {
        for (int k = cell_of(u0, g.origin.x, g.cell.x); k <= cell_of(u1, g.origin.x, g.cell.x); ++k) {
          g.bins[std::size_t(j * cells + k)].push_back(i);
        }
      }
    }
  }

  // A 3D grid of cells about three edges wide, for nearest points: a few tens of triangles per cell.
  CellGrid& grid = part.cells;
  grid.cell = std::max(3.0 * edge_sum / double(std::max<std::size_t>(count, 1)), 1e-3);
  grid.origin = lo - grid.cell;
  grid.size = glm::ivec3(glm::floor((hi - grid.origin) / grid.cell)) + 2;
  const std::size_t cell_count =
      std::size_t(grid.size.x) * std::size_t(grid.size.y) * std::size_t(grid.size.z);
  const auto index = [&](int x, int y, int z) {
    return (std::size_t(z) * std::size_t(grid.size.y) + std::size_t(y)) * std::size_t(grid.size.x) +
           std::size_t(x);
  };
  grid.offsets.assign(cell_count + 1, 0);
  std::vector<std::uint32_t> cursor;
  for (int pass = 0; pass < 2; ++pass) {  // count per cell, then fill
    if (pass == 1) {
      for (std::size_t i = 0; i < cell_count; ++i) grid.offsets[i + 1] += grid.offsets[i];
      grid.entries.resize(grid.offsets[cell_count]);
      cursor.assign(grid.offsets.begin(), grid.offsets.end() - 1);
    }
    for (std::uint32_t t = 0; t < count; ++t) {
      const Triangle& tri = part.triangles[t];
      const glm::ivec3 first(glm::floor((glm::min(tri.a, glm::min(tri.b, tri.c)) - grid.origin) / grid.cell));
      const glm::ivec3 last(glm::floor((glm::max(tri.a, glm::max(tri.b, tri.c)) - grid.origin) / grid.cell));
      for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
          for (int x = first.x; x <= last.x; ++x) {
            if (pass == 0) {
              ++grid.offsets[index(x, y, z) + 1];
            } else {
              grid.entries[cursor[index(x, y, z)]++] = t;
            }
          }
    }
  }
  return part;
}

int MeshOracle::axis_winding(const Part& part, const ProjectionGrid& g, glm::dvec3 p) {
  const int a = g.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  p[u] += 1.41421356e-9;
  p[v] += 0.73205081e-9;
  const int k = int(std::floor((p[u] - g.origin.x) / g.cell.x)),
            j = int(std::floor((p[v] - g.origin.y) / g.cell.y));
  if (k < 0 || j < 0 || k >= g.cells || j >= g.cells) return 0;
  int winding = 0;
  for (const std::uint32_t i : g.bins[std::size_t(j * g.cells + k)]) {
    const Triangle& t = part.triangles[i];
    if (t.normal[a] == 0.0) continue;  // seen edge-on
    // Is (p_u, p_v) inside the triangle's projection? Signed areas all of one sign.
    const auto side = [&](const glm::dvec3& e0, const glm::dvec3& e1) {
      return (e1[u] - e0[u]) * (p[v] - e0[v]) - (e1[v] - e0[v]) * (p[u] - e0[u]);
    };
    const double s0 = side(t.a, t.b), s1 = side(t.b, t.c), s2 = side(t.c, t.a);
    if (!((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0))) continue;
    // The crossing lies ahead along +axis when p is behind the plane as seen along +axis.
    const double behind = glm::dot(t.normal, p - t.a);
    if (behind * t.normal[a] < 0.0) winding += t.normal[a] > 0.0 ? 1 : -1;
  }
  return winding;
}

int MeshOracle::part_winding(const Part& part, const glm::dvec3& p) {
  const int w0 = axis_winding(part, part.projections[0], p), w1 = axis_winding(part, part.projections[1], p),
            w2 = axis_winding(part, part.projections[2], p);
  if (w0 == w1 || w0 == w2) return w0;
  return w1;  // w1 == w2, or all differ (then any answer is as good)
}

int MeshOracle::winding(const glm::dvec3& p) const {
  int sum = 0;
  for (const Part& part : parts_) sum += part_winding(part, p);
  return sum;
}

MeshOracle::Nearest MeshOracle::part_nearest(const Part& part, const glm::dvec3& p, double max_distance_mm,
                                             const Away& away) {
  const CellGrid& grid = part.cells;
  const glm::ivec3 centre(glm::floor((p - grid.origin) / grid.cell));
  Nearest best;
  best.distance_mm = max_distance_mm;
  const Triangle* best_triangle = nullptr;
  const int max_ring = int(std::ceil(max_distance_mm / grid.cell)) + 1;
  for (int ring = 0; ring <= max_ring; ++ring) {
    // Cells of ring r + 1 are at least r cells away from any point of the centre cell.
    if (best.distance_mm <= (ring - 1) * grid.cell) break;
    for (int z = centre.z - ring; z <= centre.z + ring; ++z)
      for (int y = centre.y - ring; y <= centre.y + ring; ++y)
        for (int x = centre.x - ring; x <= centre.x + ring; ++x) {
          if (std::max({std::abs(x - centre.x), std::abs(y - centre.y), std::abs(z - centre.z)}) != ring)
            continue;
          if (x < 0 || y < 0 || z < 0 || x >= grid.size.x || y >= grid.size.y || z >= grid.size.z) continue;
          const std::size_t i =
              (std::size_t(z) * std::size_t(grid.size.y) + std::size_t(y)) * std::size_t(grid.size.x) +
              std::size_t(x);
          for (std::uint32_t e = grid.offsets[i]; e < grid.offsets[i + 1]; ++e) {
            const Triangle& tri = part.triangles[grid.entries[e]];
            const glm::dvec3 q = nearest_point_on_triangle(p, tri.a, tri.b, tri.c);
            const double d = glm::length(p - q);
            if (d > best.distance_mm) continue;
            if (away.radius_mm > 0.0 &&
                glm::length(nearest_point_on_triangle(away.from, tri.a, tri.b, tri.c) - away.from) <=
                    away.radius_mm) {
              continue;
            }
            best.distance_mm = d, best.point = q, best.found = true, best_triangle = &tri;
          }
        }
  }
  if (best_triangle) {
    const Triangle& t = *best_triangle;
    const double area2 = glm::dot(t.normal, t.normal);
    const glm::dvec3 face = unit(t.normal, glm::dvec3(0.0, 0.0, 1.0));
    if (area2 > 0.0) {
      const double u = glm::dot(glm::cross(t.c - t.b, best.point - t.b), t.normal) / area2;
      const double v = glm::dot(glm::cross(t.a - t.c, best.point - t.c), t.normal) / area2;
      best.normal = unit(u * t.na + v * t.nb + (1.0 - u - v) * t.nc, face);
    } else {
      best.normal = face;
    }
  }
  return best;
}

MeshOracle::Nearest MeshOracle::nearest(const glm::dvec3& p, double max_distance_mm) const {
  Nearest best;
  best.distance_mm = max_distance_mm;
  for (const Part& part : parts_) {
    const Nearest n = part_nearest(part, p, best.distance_mm, {});
    if (n.found) best = n;
  }
  return best;
}

MeshOracle::Nearest MeshOracle::nearest_away(const glm::dvec3& p, double max_distance_mm,
                                             const glm::dvec3& from, double radius_mm) const {
  Nearest best;
  best.distance_mm = max_distance_mm;
  for (const Part& part : parts_) {
    const Nearest n = part_nearest(part, p, best.distance_mm, {from, radius_mm});
    if (n.found) best = n;
  }
  return best;
}

glm::dvec3 MeshOracle::outward_normal(glm::dvec3 near_surface) const {
  return nearest(near_surface, 1.0).normal;  // zero when no surface is within 1 mm
}

double MeshOracle::distance_near(glm::dvec3 p, glm::dvec3 around, double reach_mm) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Part& part : parts_) {
    const CellGrid& grid = part.cells;
    const glm::ivec3 first =
        glm::max(glm::ivec3(glm::floor((around - reach_mm - grid.origin) / grid.cell)), glm::ivec3(0));
    const glm::ivec3 last =
        glm::min(glm::ivec3(glm::floor((around + reach_mm - grid.origin) / grid.cell)), grid.size - 1);
    for (int z = first.z; z <= last.z; ++z)
      for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
          const std::size_t i =
              (std::size_t(z) * std::size_t(grid.size.y) + std::size_t(y)) * std::size_t(grid.size.x) +
              std::size_t(x);
          for (std::uint32_t e = grid.offsets[i]; e < grid.offsets[i + 1]; ++e) {
            const Triangle& t = part.triangles[grid.entries[e]];
            if (glm::length(nearest_point_on_triangle(around, t.a, t.b, t.c) - around) > reach_mm) continue;
            best = std::min(best, glm::length(nearest_point_on_triangle(p, t.a, t.b, t.c) - p));
          }
        }
  }
  return best;
}

double MeshOracle::depth_mm(glm::vec3 point) const {
  const glm::dvec3 p(point);
  double deepest = -cap_;
  bool in_any = false;
  for (const Part& part : parts_) {
    const Nearest n = part_nearest(part, p, cap_, {});
    const double d = n.found ? n.distance_mm : cap_;
    if (part_winding(part, p) > 0) {
      deepest = in_any ? std::max(deepest, d) : d;
      in_any = true;
    } else if (!in_any) {
      deepest = std::max(deepest, -d);
    }
  }
  return deepest;
}

bool MeshOracle::segment_meets_surface(const glm::dvec3& from, const glm::dvec3& to) const {
  for (const Part& part : parts_) {
    for (const Triangle& t : part.triangles) {
      if (segment_meets_triangle(from, to, t.a, t.b, t.c)) return true;
    }
  }
  return false;
}

double BumpySphereOracle::radius_at(glm::dvec3 u) const noexcept {
  return radius_mm_ + bump_mm_ * std::sin(15.0 * u.x) * std::sin(15.0 * u.y) * std::sin(15.0 * u.z + 0.7);
}

double BumpySphereOracle::implicit(glm::dvec3 p) const noexcept {
  const double r = glm::length(p);
  return radius_at(p / r) - r;
}

glm::dvec3 BumpySphereOracle::gradient(glm::dvec3 p) const noexcept {
  const double h = 1e-4;
  glm::dvec3 g;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 step(0.0);
    step[axis] = h;
    g[axis] = (implicit(p + step) - implicit(p - step)) / (2.0 * h);
  }
  return g;
}

double BumpySphereOracle::depth_mm(glm::vec3 p) const {
  return implicit(glm::dvec3(p)) / glm::length(gradient(glm::dvec3(p)));
}

glm::dvec3 BumpySphereOracle::outward_normal(glm::dvec3 near_surface) const {
  return -glm::normalize(gradient(near_surface));
}

double BumpySphereOracle::distance_near(glm::dvec3 p, glm::dvec3, double) const {
  return std::abs(depth_mm(glm::vec3(p)));
}

void BumpySphereOracle::verify(const Mesh& mesh) const {
  for (std::size_t i = 0; i < mesh.positions_mm.size(); ++i) {
    const glm::dvec3 v(mesh.positions_mm[i]);
    const double off = std::abs(glm::length(v) - radius_at(glm::normalize(v)));
    if (!(off <= 1e-3)) {
      throw Error("bumpy sphere oracle: vertex " + std::to_string(i) + " is " + std::to_string(off) +
                  " mm off the reference surface: make_bumpy_sphere changed, update BumpySphereOracle");
    }
  }
}

}  // namespace palpate::testing
