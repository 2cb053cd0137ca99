#include "palpate/core/shapes.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "mesh_expectations.hpp"
#include "palpate/core/mesh_topology.hpp"

namespace palpate {
namespace {

class SphereCount : public ::testing::TestWithParam<std::size_t> {};

TEST_P(SphereCount, HasExactlyTheVerticesAskedAndIsClosed) {
  const Mesh m = make_sphere(10.0f, GetParam());
  EXPECT_EQ(m.vertex_count(), GetParam());
  EXPECT_EQ(m.triangle_count(), 2 * GetParam() - 4);
  test::expect_sphere_topology(m);
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    EXPECT_NEAR(glm::length(m.positions_mm[v]), 10.0f, 1e-4f);
    EXPECT_GT(glm::dot(m.normals[v], m.positions_mm[v]), 9.9f);  // outward
  }
}

INSTANTIATE_TEST_SUITE_P(Counts, SphereCount, ::testing::Values(5, 6, 12, 100, 101, 1001, 68856, 90207));

TEST(BumpySphere, HasTheEvenTriangleCountNearestAndBumpsWithinRange) {
  const Mesh m = make_bumpy_sphere(50.0f, 1.5f, 53021);
  EXPECT_EQ(m.triangle_count(), 53022u);
  test::expect_sphere_topology(m);
  float lo = 1e9f, hi = 0.0f;
  for (const glm::vec3& p : m.positions_mm) {
    lo = std::min(lo, glm::length(p));
    hi = std::max(hi, glm::length(p));
  }
  EXPECT_GE(lo, 48.5f - 1e-3f);
  EXPECT_LE(hi, 51.5f + 1e-3f);
  EXPECT_GT(hi - lo, 2.0f);
}

TEST(Box, IsClosedWithOutwardNormals) {
  const Mesh m = make_box({2, 4, 6});
  const MeshTopology t = analyze_topology(m);
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.oriented());
  for (std::size_t v = 0; v < 8; ++v) EXPECT_GT(glm::dot(m.normals[v], m.positions_mm[v]), 0.0f);
  // Orientation: the signed volume of an outward-oriented box is positive.
  float volume = 0.0f;
  for (std::size_t t3 = 0; t3 < m.indices.size(); t3 += 3) {
    volume += glm::dot(m.positions_mm[m.indices[t3]],
                       glm::cross(m.positions_mm[m.indices[t3 + 1]], m.positions_mm[m.indices[t3 + 2]])) /
              6.0f;
  }
  EXPECT_NEAR(volume, 48.0f, 1e-4f);
}

TEST(Grid, HasTheExpectedCounts) {
  const Mesh m = make_grid(10.0f, 4);
  EXPECT_EQ(m.vertex_count(), 25u);
  EXPECT_EQ(m.triangle_count(), 32u);
  EXPECT_EQ(analyze_topology(m).boundary_edges, 16u);
}

}  // namespace
}  // namespace palpate
