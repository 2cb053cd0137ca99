#pragma once
// Edge topology of a mesh: is it closed, manifold and consistently oriented? (allocates)
#include <cstddef>

#include "palpate/core/mesh.hpp"

namespace palpate {

struct MeshTopology {
  std::size_t edges = 0;
  std::size_t boundary_edges = 0;        // edges in exactly one triangle
  std::size_t nonmanifold_edges = 0;     // edges in three or more triangles
  std::size_t misoriented_edges = 0;     // edges whose two triangles traverse it the same way
  std::size_t degenerate_triangles = 0;  // repeated vertex index
  std::size_t components = 0;            // connected by shared vertices
  std::size_t unreferenced_vertices = 0;
  long euler_characteristic = 0;  // V - E + F over referenced vertices

  bool closed() const noexcept { return boundary_edges == 0 && nonmanifold_edges == 0; }
  bool manifold() const noexcept { return nonmanifold_edges == 0 && degenerate_triangles == 0; }
  bool oriented() const noexcept { return misoriented_edges == 0; }
};

MeshTopology analyze_topology(const Mesh& mesh);

}  // namespace palpate
