#include "palpate/core/mesh_topology.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace palpate {
namespace {

Mesh tetrahedron() {
  Mesh m;
  m.positions_mm = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  compute_vertex_normals(m);
  return m;
}

TEST(MeshTopology, ClosedTetrahedron) {
  const MeshTopology t = analyze_topology(tetrahedron());
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.manifold());
  EXPECT_TRUE(t.oriented());
  EXPECT_EQ(t.edges, 6u);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.euler_characteristic, 2);
}

TEST(MeshTopology, OpenFlippedAndNonManifold) {
  Mesh open = tetrahedron();
  open.indices.resize(9);
  EXPECT_EQ(analyze_topology(open).boundary_edges, 3u);

  Mesh flipped = tetrahedron();
  std::swap(flipped.indices[1], flipped.indices[2]);
  EXPECT_EQ(analyze_topology(flipped).misoriented_edges, 3u);

  Mesh fin = tetrahedron();
  fin.positions_mm.push_back({1, 1, 0});
  fin.normals.push_back({0, 0, 1});
  fin.indices.insert(fin.indices.end(), {1, 2, 4});
  EXPECT_EQ(analyze_topology(fin).nonmanifold_edges, 1u);
  EXPECT_FALSE(analyze_topology(fin).manifold());
}

TEST(ComputeVertexNormals, PointOutwardOnATetrahedron) {
  const Mesh m = tetrahedron();
  const glm::vec3 centre(0.25f);
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    EXPECT_GT(glm::dot(m.normals[v], m.positions_mm[v] - centre), 0.0f);
}

}  // namespace
}  // namespace palpate
