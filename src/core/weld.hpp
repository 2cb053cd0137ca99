#pragma once
// Turning the triangles a reader produces into palpate's indexed mesh: welding equal vertices and
// computing normals where the file gives none. Setup code: allocates.
#include <glm/vec3.hpp>
#include <vector>

#include "palpate/core/mesh.hpp"

namespace palpate::detail {

// Triangle corners as a shape produced them: three per triangle, counter-clockwise, world space.
struct TriangleSoup {
  std::vector<glm::vec3> positions_mm;  // three per triangle
  std::vector<glm::vec3> normals;       // one per corner, or empty: then computed (see mesh_from_soup)
  std::vector<glm::vec3> colors;        // one per corner, or empty
};

// One vertex per distinct (position, normal, colour), compared bitwise, so a closed surface stays
// closed wherever its normals and colours are continuous. Without normals in `soup`, each corner
// gets the area-weighted normal of the faces around its position whose normal lies within
// `crease_angle_rad` of its own face's (VRML's creaseAngle: 0 gives flat faces, π fully smooth).
Mesh mesh_from_soup(const TriangleSoup& soup, float crease_angle_rad);

// Merges vertices with equal positions (bitwise) into one, for formats whose importer splits a
// position by its normal or texture coordinate (OBJ) or never shares it (STL). A merged vertex keeps
// its normal where all its uses agree and gets the area-weighted normal otherwise; its colour is its
// first use's.
void weld_positions(Mesh& mesh);

// Merges vertices equal in position, normal and colour (bitwise) into one: what assimp's
// JoinIdenticalVertices does (less texture coordinates, which palpate does not keep), in linear time.
void weld_identical(Mesh& mesh);

}  // namespace palpate::detail
