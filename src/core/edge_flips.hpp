#pragma once
// Edge flips that improve triangle shapes on a closed mesh that is star-shaped about a point.
// Private to palpate_core (the phantom generators use it).
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "palpate/core/mesh.hpp"

namespace palpate::detail {

// The corner table of a closed, consistently oriented mesh: corner c is vertex indices[c] of triangle
// c / 3, and opposite[c] is the corner facing the same edge as c from the neighbouring triangle. Throws
// palpate::Error naming an edge that has no such neighbour. Allocates.
std::vector<std::uint32_t> opposite_corners(const Mesh& mesh);

// Flips edges toward a Delaunay triangulation (the two angles facing each edge sum to at most pi), which
// removes the long thin triangles a stretched parameterization leaves. A flip is made only where
//  - the two triangles are within `max_fold_rad` of coplanar before and after, so the surface keeps its
//    shape (no edge is cut across a crease or a groove), and
//  - both new triangles still turn counter-clockwise seen from `centre`: a mesh whose every triangle does
//    so covers the directions around `centre` once, so it stays star-shaped and free of self-intersections.
// Vertices never change; `mesh.indices` and `opposite` (see opposite_corners) are kept in step. Returns
// the number of flips made. Deterministic; allocates.
std::size_t flip_toward_delaunay(Mesh& mesh, std::vector<std::uint32_t>& opposite, glm::dvec3 centre,
                                 double max_fold_rad);

}  // namespace palpate::detail
