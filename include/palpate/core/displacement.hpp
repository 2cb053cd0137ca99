#pragma once
// Where a dent moves each vertex, so that a surface whose vertices are split does not crack.
//
// Meshes split a position into several vertices wherever its normal, colour or texture coordinate
// jumps: flat shading, creases, seams, parts that touch (the paper's own models were exported with
// three vertices per face). Moved each along its own normal, the copies of one corner part and the
// surface opens. So every vertex at one position (within a tolerance, across the parts of one object)
// moves along one shared direction: the area-weighted normal of all the faces around that position.
// Shading keeps the mesh's own normals.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "palpate/core/mesh.hpp"

namespace palpate {

// The default weld tolerance of a mesh: 1e-6 of its bounds' diagonal, and at least 1e-5 mm.
float default_weld_tolerance_mm(const Mesh& mesh) noexcept;

// Vertices that share a position within `tolerance_mm` (and chains of such): group[v] is v's group,
// numbered from 0 in order of first vertex. Allocates; linear time (a hash grid).
struct PositionGroups {
  std::vector<std::uint32_t> group;  // one per vertex
  std::size_t count = 0;             // distinct positions
};
PositionGroups group_positions(const Mesh& mesh, float tolerance_mm);

// Fills mesh.directions with one unit direction per vertex, shared by every vertex at the same
// position (see above); clears it when no two vertices share a position (the normals then serve). The
// loaders call it for every mesh they read. Allocates.
void compute_displacement_directions(Mesh& mesh, float weld_tolerance_mm);
inline void compute_displacement_directions(Mesh& mesh) {
  compute_displacement_directions(mesh, default_weld_tolerance_mm(mesh));
}

// The mesh with one vertex per position (its triangles re-indexed, positions only): the surface as a
// surface, for topology (closed, manifold, components, genus) whatever its shading splits. Allocates.
Mesh weld_by_position(const Mesh& mesh, float tolerance_mm);
// The same from groups already found for `mesh` (group_positions).
Mesh weld_by_position(const Mesh& mesh, const PositionGroups& groups);

}  // namespace palpate
