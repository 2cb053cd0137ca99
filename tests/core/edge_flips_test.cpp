#include "core/edge_flips.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/radial_relaxation.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate::detail {
namespace {

double smallest_angle(const Mesh& m) {
  double smallest = 180.0;
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const std::size_t t = c / 3 * 3;
    const glm::dvec3 p(m.positions_mm[m.indices[c]]);
    const glm::dvec3 a(m.positions_mm[m.indices[t + (c - t + 1) % 3]]),
        b(m.positions_mm[m.indices[t + (c - t + 2) % 3]]);
    smallest =
        std::min(smallest, glm::degrees(std::acos(glm::dot(glm::normalize(a - p), glm::normalize(b - p)))));
  }
  return smallest;
}

// The mean over triangles of each triangle's smallest angle (60 for an all-equilateral mesh).
double mean_smallest_angle(const Mesh& m) {
  double sum = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    double smallest = 180.0;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p(m.positions_mm[m.indices[t + k]]), a(m.positions_mm[m.indices[t + (k + 1) % 3]]),
          b(m.positions_mm[m.indices[t + (k + 2) % 3]]);
      smallest =
          std::min(smallest, glm::degrees(std::acos(glm::dot(glm::normalize(a - p), glm::normalize(b - p)))));
    }
    sum += smallest;
  }
  return sum / double(m.triangle_count());
}

std::size_t facing_centre(const Mesh& m, glm::dvec3 centre) {
  std::size_t n = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 a = glm::dvec3(m.positions_mm[m.indices[t]]) - centre,
                     b = glm::dvec3(m.positions_mm[m.indices[t + 1]]) - centre,
                     c = glm::dvec3(m.positions_mm[m.indices[t + 2]]) - centre;
    if (!(glm::dot(a, glm::cross(b, c)) > 0.0)) ++n;
  }
  return n;
}

// A sphere squashed 4:1: its triangles become long and thin, and the Delaunay ones are others.
Mesh squashed_sphere() {
  Mesh m = make_sphere(40.0f, 3000);
  for (glm::vec3& p : m.positions_mm) p.z *= 0.25f;
  return m;
}

TEST(EdgeFlips, MakeASquashedSphereDelaunayAndKeepItStarShaped) {
  Mesh m = squashed_sphere();
  const double before = smallest_angle(m);
  std::vector<std::uint32_t> opposite = opposite_corners(m);
  const std::size_t flips = flip_toward_delaunay(m, opposite, glm::dvec3(0.0), glm::radians(40.0));
  EXPECT_GT(flips, 100u);
  EXPECT_GT(smallest_angle(m), before);
  EXPECT_EQ(facing_centre(m, glm::dvec3(0.0)), 0u);
  const MeshTopology t = analyze_topology(m);
  EXPECT_TRUE(t.closed() && t.manifold() && t.oriented());
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_EQ(opposite, opposite_corners(m));  // kept in step with the flips
  // Every edge still flippable under the fold limit is now Delaunay: a second pass finds nothing.
  EXPECT_EQ(flip_toward_delaunay(m, opposite, glm::dvec3(0.0), glm::radians(40.0)), 0u);
}

TEST(EdgeFlips, NeverFlipAcrossACrease) {
  // A box's edges are creases of 90 degrees: no flip may cut across one.
  Mesh box = make_box({10, 20, 30});
  const std::vector<std::uint32_t> before = box.indices;
  std::vector<std::uint32_t> opposite = opposite_corners(box);
  flip_toward_delaunay(box, opposite, glm::dvec3(0.0), glm::radians(25.0));
  for (std::size_t t = 0; t < box.indices.size(); t += 3) {
    // Each triangle still lies in one face of the box: one coordinate is shared by its three corners.
    const glm::vec3 a = box.positions_mm[box.indices[t]], b = box.positions_mm[box.indices[t + 1]],
                    c = box.positions_mm[box.indices[t + 2]];
    EXPECT_TRUE((a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y) || (a.z == b.z && b.z == c.z));
  }
}

TEST(EdgeFlips, OppositeCornersRejectAnOpenMesh) {
  Mesh open = make_sphere(1.0f, 20);
  open.indices.resize(open.indices.size() - 3);
  EXPECT_THROW(opposite_corners(open), Error);
}

TEST(RadialRelaxation, KeepsEveryVertexOnTheSurfaceAndImprovesTheTriangles) {
  // An ellipsoid as a radial function, sampled from a sphere: stretched triangles to start with.
  const RadialFunction ellipsoid = [](glm::dvec3 w) {
    return 1.0 / std::sqrt(w.x * w.x / (60.0 * 60.0) + w.y * w.y / (40.0 * 40.0) + w.z * w.z / (15.0 * 15.0));
  };
  Mesh m = make_sphere(1.0f, 4000);
  for (glm::vec3& p : m.positions_mm) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(p));
    p = glm::vec3(ellipsoid(w) * w);
  }
  const double before = mean_smallest_angle(m);
  relax_radial_mesh(m, glm::dvec3(0.0), ellipsoid, 4, glm::radians(25.0));
  EXPECT_EQ(m.vertex_count(), 4000u);
  EXPECT_EQ(m.triangle_count(), 7996u);
  for (const glm::vec3& p : m.positions_mm) {
    const glm::dvec3 q(p);
    EXPECT_NEAR(glm::length(q), ellipsoid(glm::normalize(q)), 1e-4);
  }
  EXPECT_EQ(facing_centre(m, glm::dvec3(0.0)), 0u);
  EXPECT_GT(mean_smallest_angle(m), before + 1.0);
  const MeshTopology t = analyze_topology(m);
  EXPECT_TRUE(t.closed() && t.manifold() && t.oriented());
}

}  // namespace
}  // namespace palpate::detail
