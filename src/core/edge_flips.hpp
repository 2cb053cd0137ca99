#pragma once
// Edge flips that improve triangle shapes on a closed mesh that is star-shaped about a point.
// Private to palpate_core (the phantom generators use it).
#include <cstddef>
#include <glm/vec3.hpp>

#include "palpate/core/mesh.hpp"

namespace palpate::detail {

// Flips edges toward a Delaunay triangulation (the two angles facing each edge sum to at most pi), which
// removes the long thin triangles a stretched parameterization leaves. A flip is made only where
//  - the two triangles are within `max_fold_rad` of coplanar before and after, so the surface keeps its
//    shape (no edge is cut across a crease or a sulcus), and
//  - both new triangles still turn counter-clockwise seen from `centre`: a mesh whose every triangle does
//    so covers the directions around `centre` once, so it stays star-shaped and free of self-intersections.
// Vertices and their count never change; only `mesh.indices` does. Returns the number of flips made.
// Deterministic; allocates.
std::size_t flip_toward_delaunay(Mesh& mesh, glm::dvec3 centre, double max_fold_rad);

}  // namespace palpate::detail
