#include "core/weld.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "palpate/core/mesh_topology.hpp"

namespace palpate::detail {
namespace {

// Two triangles of a square, then a third folded up along the edge x = 1 by `fold` radians, twice as
// long as the square's side (so twice the area of each half of the square).
TriangleSoup folded_strip(float fold) {
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
  const glm::vec3 e(1 + 2 * std::cos(fold), 0, 2 * std::sin(fold));
  TriangleSoup soup;
  soup.positions_mm = {a, b, c, a, c, d, b, e, c};
  return soup;
}

TEST(MeshFromSoup, CreaseAngleDecidesWhereVerticesSplit) {
  const float fold = 0.3f;
  // The square's two triangles share a and c (coplanar); the fold's corners at b and c split off.
  EXPECT_EQ(mesh_from_soup(folded_strip(fold), 0.0f).vertex_count(), 7u);
  EXPECT_EQ(mesh_from_soup(folded_strip(fold), 0.35f).vertex_count(), 5u);  // fold within the angle: shared
}

TEST(MeshFromSoup, SmoothNormalIsAreaWeighted) {
  // At b: the square's half (area 1/2, normal +z) and the folded triangle (area 1 at fold 90°, normal
  // -x): the area-weighted sum is (-1, 0, 1/2), the normal (-2, 0, 1) / sqrt(5). Weighting the two
  // faces alike would give (-1, 0, 1) / sqrt(2).
  const Mesh m = mesh_from_soup(folded_strip(std::numbers::pi_v<float> / 2), std::numbers::pi_v<float>);
  int found = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    if (m.positions_mm[v] != glm::vec3(1, 0, 0)) continue;
    ++found;
    EXPECT_NEAR(m.normals[v].x, -2.0f / std::sqrt(5.0f), 1e-6f);
    EXPECT_NEAR(m.normals[v].y, 0.0f, 1e-6f);
    EXPECT_NEAR(m.normals[v].z, 1.0f / std::sqrt(5.0f), 1e-6f);
  }
  EXPECT_EQ(found, 1) << "b is one smooth vertex";
}

TEST(MeshFromSoup, ColoursSplitVertices) {
  TriangleSoup soup = folded_strip(0.0f);
  soup.colors = {glm::vec3(1, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 0, 0),
                 glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0),
                 glm::vec3(1, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 0, 0)};
  const Mesh m = mesh_from_soup(soup, std::numbers::pi_v<float>);
  EXPECT_EQ(m.vertex_count(), 7u);  // a and c in two colours each, b, d and e in one
  EXPECT_EQ(m.colors.size(), 7u);
}

TEST(WeldPositions, MergesEqualPositionsAndKeepsAgreeingNormals) {
  Mesh m;
  m.positions_mm = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(6, glm::vec3(0, 0, 1));
  m.indices = {0, 1, 2, 3, 4, 5};
  weld_positions(m);
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
  for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  EXPECT_EQ(analyze_topology(m).boundary_edges, 4u);
}

}  // namespace
}  // namespace palpate::detail
