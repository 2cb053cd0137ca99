#pragma once
// Inside test and depth for closed meshes, independent of palpate's BVH and proxy: the reference
// the bench checks a path scenario against on a mesh without an analytic surface (the Table I
// meshes). A uniform grid of triangles per object; inside by the parity of a +z ray's crossings,
// distance by the nearest triangle in growing rings of cells. Not for the haptic tick (tens of
// microseconds a query); built for checking, and written plainly so it is easy to trust.
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "palpate/core/scene.hpp"
#include "surface_reference.hpp"

namespace palpate::cli {

class MeshReference final : public SurfaceReference {
 public:
  // Every object of `scene` must be closed (the parity test needs it). Allocates.
  explicit MeshReference(const Scene& scene, float depth_cap_mm = 8.0f);

  // Signed distance below the surface, positive inside: for the objects containing `p`, the largest
  // distance to that object's surface; outside all, minus the distance to the nearest. Magnitudes
  // are capped at the depth cap.
  double depth_mm(glm::vec3 p) const override;
  double depth_limit_mm() const override { return cap_; }

 private:
  struct Triangle {
    glm::dvec3 a, b, c;
  };
  struct Grid {
    std::vector<Triangle> triangles;
    glm::dvec3 origin{0.0};
    double cell = 1.0;
    glm::ivec3 size{1};
    std::vector<std::uint32_t> offsets;  // cell -> first entry in `entries`; size cells + 1
    std::vector<std::uint32_t> entries;  // triangle indices, grouped by cell
  };
  static Grid build(const SceneObject& object);
  bool inside(const Grid& grid, glm::dvec3 p) const;
  double distance(const Grid& grid, glm::dvec3 p) const;

  std::vector<Grid> grids_;
  double cap_;
};

}  // namespace palpate::cli
