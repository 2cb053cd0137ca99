#pragma once
// The per-vertex data of the geodesic falloff: for the vertices a dent reaches along the surface (its
// patch, out to 4 sigma), the distance from the contact over the surface and the unit direction toward
// the contact along it, as the surface samples the deformation reads (palpate/core/deform.hpp); every
// other vertex holds no_surface_sample, where the dent's weight is zero.
//
// Each frame, compute() marches over the undeformed mesh from the contact (GeodesicField) and rewrites
// the samples of the last patch and the new one only; changed() says which vertices to upload. Vertices
// split at one position (flat shading, creases) are welded for the march, so the front crosses their
// seams, and every copy gets the same sample.
//
//     palpate::SurfacePatch patch(mesh);                  // once: adjacency and workspace
//     ...each frame, for the object's first dent (object frame):
//     dent = palpate::dent_with_slope_limit(dent, palpate::surface_dent_max_slope);
//     patch.compute(contact_triangle, contact_point, 4 * dent.sigma_mm);
//     upload patch.samples()[changed.first, changed.first + changed.count) into the vertex attribute
//     dent.along_surface = true;
//     dent.normal = the rotation to the dent's space * patch.contact_normal();
#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <span>
#include <vector>

#include "palpate/core/deform.hpp"
#include "palpate/core/displacement.hpp"
#include "palpate/core/geodesic.hpp"
#include "palpate/core/mesh.hpp"

namespace palpate {

class SurfacePatch {
 public:
  // A range of vertices [first, first + count).
  struct Range {
    std::uint32_t first = 0, count = 0;
  };

  // Copies what it needs of `mesh` (its positions and triangles, welded by position). Allocates.
  explicit SurfacePatch(const Mesh& mesh);
  SurfacePatch(const SurfacePatch&) = delete;  // its field refers to its own welded mesh
  SurfacePatch& operator=(const SurfacePatch&) = delete;

  // The patch of a dent at `point_mm` (object frame) on triangle `triangle` of the mesh, out to
  // `radius_mm` along the surface. A triangle out of range (-1: unknown) is found as the one closest to
  // the point, by a scan of the whole mesh (about 1 ms per 100,000 triangles): pass it when known. No
  // allocation.
  void compute(std::int64_t triangle, glm::vec3 point_mm, float radius_mm) noexcept;
  // No dent: the last patch goes back to no_surface_sample. No allocation.
  void clear() noexcept;

  // One sample per vertex of the mesh (object frame).
  std::span<const glm::vec4> samples() const noexcept { return samples_; }
  // The vertices whose samples the last compute() or clear() rewrote: the last patch and the new one.
  Range changed() const noexcept { return changed_; }
  // The contact triangle's outward unit normal, object frame (Dent::normal once taken to world).
  glm::vec3 contact_normal() const noexcept { return contact_normal_; }
  // Vertices (welded) in the current patch.
  std::size_t size() const noexcept { return patch_.size(); }

 private:
  SurfacePatch(const Mesh& mesh, const PositionGroups& groups);
  std::uint32_t closest_triangle(glm::vec3 point_mm) const noexcept;
  void write(std::uint32_t welded_vertex, glm::vec4 sample) noexcept;

  Mesh welded_;
  std::vector<std::uint32_t> first_copy_, copies_;  // the mesh's vertices at each welded vertex
  GeodesicField field_;
  std::vector<glm::vec4> samples_;
  std::vector<glm::vec3> gradient_sum_;  // per welded vertex, scratch
  std::vector<std::uint32_t> patch_;     // welded vertices with a sample now
  Range changed_;
  glm::vec3 contact_normal_{0.0f};
};

}  // namespace palpate
