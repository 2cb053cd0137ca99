#pragma once
// Expectations on generated surfaces shared by the shape and phantom tests.
#include <gtest/gtest.h>

#include "palpate/core/mesh_topology.hpp"

namespace palpate::test {

// A closed, manifold, consistently oriented surface of one piece with the topology of a sphere, every
// vertex used.
inline void expect_sphere_topology(const Mesh& m) {
  const MeshTopology t = analyze_topology(m);
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.manifold());
  EXPECT_TRUE(t.oriented());
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_EQ(t.unreferenced_vertices, 0u);
}

}  // namespace palpate::test
