#pragma once
// Generated test anatomy, deterministic and downloaded from nowhere: closed, manifold, consistently
// oriented (outward normals, counter-clockwise) surfaces in millimetres.
// Default sizes are the paper's Table I: brain 68,856 vertices, skin 90,207 vertices. A closed genus-0
// surface has 2V - 4 triangles; the paper's face counts (22,952 and 30,069) are a third of its vertex
// counts, i.e. it counted unshared triangle corners.
#include <cstddef>
#include <glm/vec3.hpp>

#include "palpate/core/mesh.hpp"

namespace palpate {

inline constexpr std::size_t brain_phantom_vertices = 68856;
inline constexpr std::size_t skin_phantom_vertices = 90207;
inline constexpr std::size_t phantom_min_vertices = 500;

// Frame: x to the right, y to the front (the face), z up; origin at the brain's centre.
// Each surface is star-shaped about its point below: every triangle turns counter-clockwise seen from it,
// and each ray from it crosses the surface once. So neither surface can intersect itself, and "inside"
// is a comparison of distances along that ray.
inline constexpr glm::vec3 brain_phantom_star_centre{0.0f, 0.0f, 0.0f};
inline constexpr glm::vec3 skin_phantom_star_centre{0.0f, -15.0f, -75.0f};

// Two hemispheres about 140 x 165 x 115 mm (x, y, z) split by a longitudinal fissure 25 mm deep whose
// banks are a few mm apart, with meandering gyri and sulci a few mm wide and 10-13 mm deep, temporal
// lobes lower at the sides and a flattened base. Coarser meshes get shallower grooves: sulci appear from
// about 10,000 vertices and reach their full depth at 30,000, the fissure from about 2,700 to 11,000. Exactly
// `vertices` vertices and 2 * vertices - 4 triangles. Deterministic. Throws palpate::Error for fewer than
// phantom_min_vertices.
Mesh make_brain_phantom(std::size_t vertices = brain_phantom_vertices);

// A head with a cranium, forehead, face (brows, eye sockets, nose, lips, chin) and a neck stub, about
// 195 mm from the back of the head to the forehead (219 to the tip of the nose) and 164 mm wide,
// enclosing the brain with a gap of about 10 mm or more for skull and CSF. Exactly `vertices` vertices and 2
// * vertices - 4 triangles. Deterministic. Throws palpate::Error for fewer than phantom_min_vertices.
Mesh make_skin_phantom(std::size_t vertices = skin_phantom_vertices);

}  // namespace palpate
