#include "palpate/testing/surface_checks.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <unordered_map>
#include <utility>
#include <vector>

#include "palpate/core/deform.hpp"
#include "palpate/core/surface_patch.hpp"

namespace palpate::testing {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using ShortestPaths =
    CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>>;

Kernel::Point_3 point_of(glm::vec3 p) {
  return {p.x, p.y, p.z};
}

Kernel::Triangle_3 triangle_of(const Mesh& mesh, std::size_t t) {
  return {point_of(mesh.positions_mm[mesh.indices[3 * t]]),
          point_of(mesh.positions_mm[mesh.indices[3 * t + 1]]),
          point_of(mesh.positions_mm[mesh.indices[3 * t + 2]])};
}

}  // namespace

WeightErrors weight_errors_against_exact(const Mesh& mesh, std::uint32_t triangle, glm::vec3 point_mm,
                                         float sigma_mm,
                                         const std::function<float(std::uint32_t)>& distance) {
  const float reach = 4.0f * sigma_mm, patch = reach + 2.0f;
  SurfaceMesh exact_mesh;
  std::unordered_map<std::uint32_t, SurfaceMesh::Vertex_index> to_exact;
  SurfaceMesh::Face_index source_face;
  std::size_t left_out = 0;
  const auto vertex = [&](std::uint32_t v) {
    const auto found = to_exact.find(v);
    if (found != to_exact.end()) return found->second;
    return to_exact[v] = exact_mesh.add_vertex(point_of(mesh.positions_mm[v]));
  };
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t* c = &mesh.indices[3 * std::size_t(t)];
    if (std::max({glm::distance(mesh.positions_mm[c[0]], point_mm),
                  glm::distance(mesh.positions_mm[c[1]], point_mm),
                  glm::distance(mesh.positions_mm[c[2]], point_mm)}) > patch)
      continue;
    const auto face = exact_mesh.add_face(vertex(c[0]), vertex(c[1]), vertex(c[2]));
    left_out += face == SurfaceMesh::null_face();
    if (t == triangle) source_face = face;
  }
  WeightErrors errors;
  errors.faces_left_out = left_out;
  if (source_face == SurfaceMesh::null_face()) return errors;  // not addable (non-manifold there)
  // The point's barycentric coordinates in its triangle.
  const std::uint32_t* c = &mesh.indices[3 * std::size_t(triangle)];
  const glm::vec3 a = mesh.positions_mm[c[0]], b = mesh.positions_mm[c[1]], cc = mesh.positions_mm[c[2]];
  const glm::vec3 n = glm::cross(b - a, cc - a);
  const float area = glm::dot(n, n);
  const float u = glm::dot(glm::cross(cc - b, point_mm - b), n) / area;
  const float v = glm::dot(glm::cross(a - cc, point_mm - cc), n) / area;
  // CGAL's barycentric coordinates go with the face's corners in the order source(h), target(h),
  // target(next(h)) of its halfedge h, which need not start at c[0].
  const double by_corner[3] = {double(u), double(v), double(1.0f - u - v)};
  const auto h = exact_mesh.halfedge(source_face);
  const SurfaceMesh::Vertex_index order[3] = {exact_mesh.source(h), exact_mesh.target(h),
                                              exact_mesh.target(exact_mesh.next(h))};
  ShortestPaths::Barycentric_coordinates coordinates{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      if (to_exact.at(c[j]) == order[k]) coordinates[k] = by_corner[j];
  ShortestPaths exact(exact_mesh);
  exact.add_source_point(source_face, coordinates);
  const auto weight = [&](double d) {
    return d < reach ? std::exp(-d * d / (2.0 * sigma_mm * sigma_mm)) : 0.0;
  };
  for (const auto& [vertex_index, exact_vertex] : to_exact) {
    const double exact_distance = exact.shortest_distance_to_source_points(exact_vertex).first;
    if (exact_distance < 0.0 || exact_distance > reach) continue;  // -1: not connected within the patch
    const double signed_error = weight(distance(vertex_index)) - weight(exact_distance);
    const double error = std::abs(signed_error);
    if (error > errors.max) errors.max_signed = signed_error;
    errors.max = std::max(errors.max, error);
    errors.mean += error;
    ++errors.vertices;
  }
  errors.mean /= double(std::max<std::size_t>(errors.vertices, 1));
  return errors;
}

FoldCounts count_folds(const Mesh& undeformed, const Mesh& deformed, glm::vec3 center_mm, float radius_mm) {
  // The triangles near the dent, and every triangle whose deformed box meets theirs, in a grid.
  const std::size_t triangles = undeformed.indices.size() / 3;
  std::vector<std::uint32_t> near;
  glm::vec3 low(INFINITY), high(-INFINITY);
  const auto box_of = [&](const Mesh& mesh, std::size_t t, glm::vec3& lo, glm::vec3& hi) {
    lo = hi = mesh.positions_mm[mesh.indices[3 * t]];
    for (int k = 1; k < 3; ++k) {
      lo = glm::min(lo, mesh.positions_mm[mesh.indices[3 * t + k]]);
      hi = glm::max(hi, mesh.positions_mm[mesh.indices[3 * t + k]]);
    }
  };
  for (std::size_t t = 0; t < triangles; ++t) {
    bool inside = false;
    for (int k = 0; k < 3; ++k)
      inside = inside ||
               glm::distance(undeformed.positions_mm[undeformed.indices[3 * t + k]], center_mm) < radius_mm;
    if (!inside) continue;
    near.push_back(std::uint32_t(t));
    glm::vec3 lo, hi;
    box_of(deformed, t, lo, hi);
    low = glm::min(low, lo);
    high = glm::max(high, hi);
  }
  FoldCounts counts;
  if (near.empty()) return counts;
  std::vector<std::uint32_t> candidates;
  for (std::size_t t = 0; t < triangles; ++t) {
    glm::vec3 lo, hi;
    box_of(deformed, t, lo, hi);
    if (glm::all(glm::lessThanEqual(lo, high)) && glm::all(glm::lessThanEqual(low, hi)))
      candidates.push_back(std::uint32_t(t));
  }
  constexpr float cell = 2.0f;
  const glm::ivec3 cells = glm::ivec3((high - low) / cell) + 1;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  const auto key = [&](glm::ivec3 i) { return (std::int64_t(i.z) * cells.y + i.y) * cells.x + i.x; };
  for (const std::uint32_t t : candidates) {
    glm::vec3 lo, hi;
    box_of(deformed, t, lo, hi);
    const glm::ivec3 from = glm::max(glm::ivec3((lo - low) / cell), glm::ivec3(0));
    const glm::ivec3 to = glm::min(glm::ivec3((hi - low) / cell), cells - 1);
    for (int z = from.z; z <= to.z; ++z)
      for (int y = from.y; y <= to.y; ++y)
        for (int x = from.x; x <= to.x; ++x) grid[key({x, y, z})].push_back(t);
  }
  const auto share_a_corner = [&](std::uint32_t s, std::uint32_t t) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (undeformed.positions_mm[undeformed.indices[3 * s + i]] ==
            undeformed.positions_mm[undeformed.indices[3 * t + j]])
          return true;
    return false;
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const auto& [cell_key, members] : grid) {
    for (std::size_t i = 0; i < members.size(); ++i)
      for (std::size_t j = i + 1; j < members.size(); ++j)
        pairs.emplace_back(std::min(members[i], members[j]), std::max(members[i], members[j]));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::uint8_t> crossing(triangles, 0);
  const auto is_near = [&](std::uint32_t t) { return std::binary_search(near.begin(), near.end(), t); };
  for (const auto& [s, t] : pairs) {
    if (!is_near(s) && !is_near(t)) continue;
    if (share_a_corner(s, t)) continue;
    if (!CGAL::do_intersect(triangle_of(deformed, s), triangle_of(deformed, t))) continue;
    if (CGAL::do_intersect(triangle_of(undeformed, s), triangle_of(undeformed, t))) continue;
    crossing[s] = crossing[t] = 1;
  }
  for (const std::uint32_t t : near) {
    counts.self_intersecting += crossing[t];
    const auto normal = [&](const Mesh& mesh) {
      const glm::vec3 a = mesh.positions_mm[mesh.indices[3 * t]];
      return glm::cross(mesh.positions_mm[mesh.indices[3 * t + 1]] - a,
                        mesh.positions_mm[mesh.indices[3 * t + 2]] - a);
    };
    counts.inverted += glm::dot(normal(undeformed), normal(deformed)) < 0.0f;
  }
  return counts;
}

std::vector<PressSite> spread_press_sites(const Mesh& mesh, std::size_t count) {
  std::vector<PressSite> sites(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t triangle = std::uint32_t((101 + i * 7919) % mesh.triangle_count());
    sites[i] = {triangle, (mesh.positions_mm[mesh.indices[3 * triangle]] +
                           mesh.positions_mm[mesh.indices[3 * triangle + 1]] +
                           mesh.positions_mm[mesh.indices[3 * triangle + 2]]) /
                              3.0f};
  }
  return sites;
}

FoldCounts folds_of_presses(const Mesh& mesh, bool walls_give_way, float depth_over_sigma,
                            std::size_t presses) {
  constexpr float sigma_mm = 4.0f;
  SurfacePatch patch(mesh);
  Mesh deformed;
  FoldCounts total;
  for (const auto& [triangle, point] : spread_press_sites(mesh, presses)) {
    Dent dent =
        dent_with_slope_limit(Dent{point, depth_over_sigma * sigma_mm, sigma_mm}, surface_dent_max_slope);
    if (walls_give_way) {
      patch.compute(triangle, point, SurfacePatch::PushedDent{dent.depth_mm, dent.sigma_mm});
    } else {
      patch.compute(triangle, point, dent_cutoff_sigmas * dent.sigma_mm);
    }
    dent.along_surface = true;
    dent.normal = patch.contact_normal();
    deform_mesh(mesh, glm::mat4(1.0f), {&dent, 1}, deformed, patch.samples());
    const FoldCounts counts = count_folds(mesh, deformed, point, dent_cutoff_sigmas * sigma_mm);
    total.self_intersecting += counts.self_intersecting;
    total.inverted += counts.inverted;
  }
  return total;
}

}  // namespace palpate::testing
