#pragma once
// Evening out the vertices of a closed mesh that is a radial graph about a point. Private to palpate_core.
#include <functional>
#include <glm/vec3.hpp>

#include "palpate/core/mesh.hpp"

namespace palpate::detail {

// The distance (mm) from the centre to the surface in a unit direction.
using RadialFunction = std::function<double(glm::dvec3 direction)>;

// `iterations` rounds of: Delaunay edge flips (see edge_flips.hpp), then each vertex moves halfway toward
// the mean of its neighbours within the surface's tangent plane and back onto the surface along its ray
// from `centre`; then up to three rounds that move only the corners of triangles sharper than about 12
// degrees, toward the area-weighted centroid of their triangles (which pulls crowded vertices apart).
// A move that would turn a triangle over (seen from the centre) is undone, so the mesh stays star-shaped
// about `centre`. Every vertex stays on the surface; the vertex count and the genus do not change. Ends
// with a round of flips and leaves `mesh.normals` to the caller. Allocates.
void relax_radial_mesh(Mesh& mesh, glm::dvec3 centre, const RadialFunction& radius, int iterations,
                       double max_fold_rad);

}  // namespace palpate::detail
