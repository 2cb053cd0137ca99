// palpate's fast-marching distances against CGAL's exact shortest paths (Surface_mesh_shortest_path,
// the reference only: exact, but seconds per source) on the folded phantom brain: the dent's weight
// exp(-d^2 / 2 sigma^2) within its reach, as a fraction of the penetration depth.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <unordered_map>

#include "palpate/core/geodesic.hpp"
#include "palpate/core/phantom.hpp"

namespace palpate {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using ShortestPaths =
    CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>>;

struct WeightErrors {
  double mean = 0.0, max = 0.0;
  std::size_t vertices = 0;
};

// The triangles whose corners all lie within `patch_mm` of `centre` (straight-line distances bound the
// surface ones from below, so every path shorter than that stays inside), as a CGAL mesh.
WeightErrors compare_at(const Mesh& mesh, std::uint32_t triangle, float sigma_mm) {
  const glm::vec3 point =
      (mesh.positions_mm[mesh.indices[3 * triangle]] + mesh.positions_mm[mesh.indices[3 * triangle + 1]] +
       mesh.positions_mm[mesh.indices[3 * triangle + 2]]) /
      3.0f;
  const float reach = 4.0f * sigma_mm, patch = reach + 2.0f;
  SurfaceMesh exact_mesh;
  std::unordered_map<std::uint32_t, SurfaceMesh::Vertex_index> to_exact;
  SurfaceMesh::Face_index source_face;
  const auto vertex = [&](std::uint32_t v) {
    const auto found = to_exact.find(v);
    if (found != to_exact.end()) return found->second;
    const glm::vec3 p = mesh.positions_mm[v];
    return to_exact[v] = exact_mesh.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
  };
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t* c = &mesh.indices[3 * std::size_t(t)];
    if (std::max({glm::distance(mesh.positions_mm[c[0]], point),
                  glm::distance(mesh.positions_mm[c[1]], point),
                  glm::distance(mesh.positions_mm[c[2]], point)}) > patch)
      continue;
    const auto face = exact_mesh.add_face(vertex(c[0]), vertex(c[1]), vertex(c[2]));
    if (t == triangle) source_face = face;
  }
  ShortestPaths exact(exact_mesh);
  exact.add_source_point(source_face, {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}});

  GeodesicField field(mesh);
  field.compute(triangle, point, reach);
  WeightErrors errors;
  const auto weight = [&](double d) {
    return d < reach ? std::exp(-d * d / (2.0 * sigma_mm * sigma_mm)) : 0.0;
  };
  for (const auto& [v, exact_vertex] : to_exact) {
    const double exact_distance = exact.shortest_distance_to_source_points(exact_vertex).first;
    if (exact_distance < 0.0 || exact_distance > reach) continue;  // -1: not connected within the patch
    const double error = std::abs(weight(field.distance_mm(v)) - weight(exact_distance));
    errors.max = std::max(errors.max, error);
    errors.mean += error;
    ++errors.vertices;
  }
  errors.mean /= double(std::max<std::size_t>(errors.vertices, 1));
  return errors;
}

TEST(GeodesicAgainstExact, TheDentsWeightOnTheFoldedBrainIsCloseToTheExactOne) {
  const Mesh brain = make_brain_phantom();
  double worst = 0.0, mean = 0.0;
  int contacts = 0;
  for (std::uint32_t triangle = 101; triangle < brain.triangle_count(); triangle += 9973) {
    const WeightErrors errors = compare_at(brain, triangle, 4.0f);
    std::printf("triangle %u: %zu vertices within 4 sigma, weight error mean %.4f, max %.4f of p\n", triangle,
                errors.vertices, errors.mean, errors.max);
    worst = std::max(worst, errors.max);
    mean += errors.mean;
    ++contacts;
  }
  mean /= contacts;
  std::printf("%d contacts, sigma 4 mm: weight error mean %.4f, max %.4f of p\n", contacts, mean, worst);
  // Measured: mean 0.0005, max 0.051 of p (issue 14's target, 0.03, is not met yet: the worst vertices
  // lie over the phantom's sharp crests; on the decimated Colin27 brain max 0.082).
  EXPECT_LE(mean, 0.002);
  EXPECT_LE(worst, 0.07);
}

}  // namespace
}  // namespace palpate
