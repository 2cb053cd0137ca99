#pragma once
// Edge topology of a mesh: is it closed, manifold and consistently oriented? By vertex index: weld a
// mesh with split vertices first (weld_by_position, palpate/core/displacement.hpp) to see its surface.
// Allocates.
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
  // Handles of a closed, manifold, oriented surface, summed over its components: (2 C - chi) / 2.
  long genus() const noexcept { return (2 * long(components) - euler_characteristic) / 2; }
};

MeshTopology analyze_topology(const Mesh& mesh);

}  // namespace palpate
