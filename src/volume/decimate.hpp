#pragma once
// Edge collapses that keep a surface's topology, through CGAL's Surface_mesh_simplification (Garland
// and Heckbert's quadrics, each collapse checked against the link condition). meshoptimizer 0.18 and
// VTK's decimators both pinch close sulcal banks into non-manifold edges (measured on Colin27's
// brain: 11 and 67 edges), which the proxy and the dent would then meet.
#include <cstddef>
#include <filesystem>

#include "palpate/core/mesh.hpp"

namespace palpate::volume {

// Collapses edges of the closed or open manifold `mesh` (positions and indices; normals are left to the
// caller) until it has at most `triangles` triangles or no collapse keeps its topology. Throws
// palpate::Error naming `source` when the mesh is not a manifold CGAL can hold.
void decimate_keeping_topology(Mesh& mesh, std::size_t triangles, const std::filesystem::path& source);

}  // namespace palpate::volume
