#pragma once
// Test scenes for the haptic core: shapes with the concave creases, corners and slots that a god-object
// must handle.
#include <cstddef>
#include <string>

#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::testing {

// A scene of one touchable object.
Scene scene_of(const std::string& name, Mesh mesh);

// A closed cube of `outer` mm with a cubic cavity of `inner` mm at its centre: from inside the cavity
// every wall meets the next in a concave crease and every corner is a concave three-plane corner.
Mesh make_hollow_box(float outer_mm, float inner_mm);

// A closed comb: a base block with `teeth` teeth, extruded `depth` mm along z. The gaps between teeth
// are narrow concave slots (like sulci) with concave creases at their bottoms and convex edges on top.
Mesh make_comb(int teeth, float tooth_width_mm, float gap_mm, float tooth_height_mm, float base_height_mm,
               float depth_mm);

// A closed torus about the z axis: tube centre `major_mm` from the axis, tube radius `minor_mm`,
// `segments` steps around the axis and `sides` around the tube; smooth (shared vertices).
Mesh make_torus(float major_mm, float minor_mm, int segments, int sides);

// A sulcus unrolled: a 100 x 100 mm sheet (1 mm cells) bent back on itself, the lower part at z = 0 for
// x in [0, 40], a half cylinder of radius 3 mm about the y axis at x = 40, z = 3, and the upper part at
// z = 6 back over the lower. Points facing across the gap are 6 mm apart through the air and 20 mm or
// more apart along the surface. Open, smooth (shared vertices); the lower part faces +z, the upper -z.
Mesh make_folded_sheet();

// A 60 x 60 mm sheet of `cells` x `cells` squares at height z, facing +z or -z, added to `mesh`.
void add_sheet(Mesh& mesh, float z, std::size_t cells, bool facing_up);

// The mesh flat-shaded as exporters write it: three vertices of its own for every triangle, each with
// the face's normal (so no two triangles share a vertex, though their corners coincide).
Mesh split_flat(const Mesh& mesh);

}  // namespace palpate::testing
