#pragma once
// Checks of a dent's falloff and of the deformed surface, exact and slow (CGAL): for tests and
// benchmarks, never per frame.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/vec3.hpp>
#include <vector>

#include "palpate/core/mesh.hpp"

namespace palpate::testing {

// The dent's weight exp(-d^2 / 2 sigma^2) within its reach (4 sigma) with palpate's `distance` of each
// vertex, against the weight with CGAL's exact shortest path from `point_mm` on `triangle`, as a
// fraction of the penetration depth, over the vertices the exact path reaches within 4 sigma. The
// exact paths run on the triangles within 4 sigma + 2 mm of the point (straight lines bound the
// surface paths from below, so no shorter path leaves them). Seconds per contact at sigma 8 mm.
struct WeightErrors {
  double mean = 0.0, max = 0.0;
  double max_signed = 0.0;  // the largest error with its sign: > 0 where palpate's weight is the larger
  std::size_t vertices = 0;
  std::size_t faces_left_out = 0;  // triangles CGAL's mesh could not take (non-manifold there)
};
WeightErrors weight_errors_against_exact(const Mesh& mesh, std::uint32_t triangle, glm::vec3 point_mm,
                                         float sigma_mm, const std::function<float(std::uint32_t)>& distance);

// The triangles near a dent that the deformation made pass through another or turn over: among the
// triangles with a corner within `radius_mm` of `center_mm` (undeformed), those of `deformed` (the same
// triangles, moved) that cross a triangle they did not cross undeformed and share no corner position
// with (exact predicates), and those whose normal turned against the undeformed one.
struct FoldCounts {
  std::size_t self_intersecting = 0, inverted = 0;
};
FoldCounts count_folds(const Mesh& undeformed, const Mesh& deformed, glm::vec3 center_mm, float radius_mm);

// `count` triangles spread over `mesh` (the same for every run), each with its centroid.
struct PressSite {
  std::uint32_t triangle;
  glm::vec3 point_mm;
};
std::vector<PressSite> spread_press_sites(const Mesh& mesh, std::size_t count);

// Presses of depth `depth_over_sigma` sigma (4 mm, widened as the renderer widens it) at the centroids
// of `presses` triangles spread over `mesh` (spread_press_sites), falling off along the surface, with the
// walls behind the dent giving way (SurfacePatch::PushedDent) or not; their folds summed.
FoldCounts folds_of_presses(const Mesh& mesh, bool walls_give_way, float depth_over_sigma,
                            std::size_t presses);

}  // namespace palpate::testing
