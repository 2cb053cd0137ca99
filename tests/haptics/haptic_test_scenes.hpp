#pragma once
// Test scenes for the haptic core, and an inside test that shares no code with the BVH.
#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::test {

// A scene of one touchable object.
Scene scene_of(const std::string& name, Mesh mesh);

// A closed cube of `outer` mm with a cubic cavity of `inner` mm at its centre: from inside the cavity
// every wall meets the next in a concave crease and every corner is a concave three-plane corner.
Mesh make_hollow_box(float outer_mm, float inner_mm);

// A closed comb: a base block with `teeth` teeth, extruded `depth` mm along z. The gaps between teeth
// are narrow concave slots (like sulci) with concave creases at their bottoms and convex edges on top.
Mesh make_comb(int teeth, float tooth_width_mm, float gap_mm, float tooth_height_mm, float base_height_mm,
               float depth_mm);

// Winding number of the scene's touchable closed surfaces around points, by counting signed crossings
// of rays along +x, +y and +z (each through a 2D grid of the triangles' projections) and taking the
// majority. Each ray is moved sideways by ~1e-9 mm in an irrational direction, so it does not run
// exactly through a projected edge (a symmetric corner lies on the diagonals of all three faces).
class InsideReference {
 public:
  explicit InsideReference(const Scene& scene);

  int winding(const glm::dvec3& p) const;
  bool inside(const glm::dvec3& p) const { return winding(p) > 0; }
  // Whether the segment meets any triangle (either side, boundary included): brute force.
  bool segment_meets_surface(const glm::dvec3& from, const glm::dvec3& to) const;
  std::size_t triangle_count() const noexcept { return triangles_.size(); }

 private:
  struct Triangle {
    glm::dvec3 a, b, c, normal;
  };
  struct Grid {  // triangles by the cell of their projection along one axis
    int axis = 0;
    glm::dvec2 origin{0.0}, cell{1.0};
    int cells = 1;
    std::vector<std::vector<std::uint32_t>> bins;
  };

  int axis_winding(const Grid& grid, glm::dvec3 p) const;

  std::vector<Triangle> triangles_;
  Grid grids_[3];
};

}  // namespace palpate::test
