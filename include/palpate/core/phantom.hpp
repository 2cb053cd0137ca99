#pragma once
// Generated test anatomy, deterministic and downloaded from nowhere: closed, manifold, consistently
// oriented (outward normals, counter-clockwise) surfaces in millimetres.
// Default sizes are the paper's Table I: brain 68,856 vertices, skin 90,207 vertices. A closed genus-0
// surface has 2V - 4 triangles; the paper's face counts (22,952 and 30,069) are a third of its vertex
// counts, i.e. it counted unshared triangle corners.
#include <cstddef>

#include "palpate/core/mesh.hpp"

namespace palpate {

inline constexpr std::size_t brain_phantom_vertices = 68856;
inline constexpr std::size_t skin_phantom_vertices = 90207;

// Two hemispheres with gyri, narrow deep sulci and a longitudinal fissure, about 165 mm long.
// Centred in the skin's frame. Throws palpate::Error for a vertex count too small to build.
Mesh make_brain_phantom(std::size_t vertices = brain_phantom_vertices);

// A head-shaped scalp, about 190 mm long, that encloses the brain with a gap for skull and CSF.
Mesh make_skin_phantom(std::size_t vertices = skin_phantom_vertices);

}  // namespace palpate
