#pragma once
// Distances along a mesh's surface from a point on it, out to a radius: the falloff of a dent measured
// over the surface, so that a press on one bank of a sulcus leaves the facing bank alone (the paper's
// named limit of its Euclidean falloff).
//
// Fast marching on the triangles (Kimmel and Sethian, 1998): the front leaves the contact triangle's
// three corners with their in-plane distances and crosses each triangle from the virtual point source
// that its two known corners place in its plane; at an obtuse corner the neighbouring triangle is
// unfolded into the plane, so the front is not forced along edges there. A triangle whose corners the
// front reached from either side of a saddle vertex or a fold (its source proves false) is crossed
// through its neighbour instead. Once all are known, a vertex the front still reached along an edge is
// updated again, and one whose source could not be checked then is computed afresh. Written here: no Debian
// library marches on a triangle mesh with a workspace reused per frame (CGAL's exact shortest paths serve as
// the test's reference: exact, but far too slow per frame).
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <span>
#include <vector>

#include "palpate/core/mesh.hpp"

namespace palpate {

class GeodesicField {
 public:
  // Builds the mesh's adjacency and sizes the workspace once. The mesh must outlive the field.
  explicit GeodesicField(const Mesh& mesh);

  // Marches from `point_mm` (on triangle `triangle`, the t-th of Mesh::indices / 3) until the front
  // passes `radius_mm`. The second look after the march (which puts right the vertices the front reached
  // along an edge, and those after them) stops at `second_look_mm` but for the neighbours of a vertex it
  // changed by over 1%: beyond it a distance may stay a few percent long, as in a dent's tail where that
  // no longer matters. No allocation. Throws palpate::Error for a triangle out of range.
  void compute(std::uint32_t triangle, glm::vec3 point_mm, float radius_mm,
               float second_look_mm = std::numeric_limits<float>::infinity());

  // The vertices within the radius, from the last compute(), in the order the front reached them
  // (nearest first but for the vertices corrected afterwards, moved by a few percent, rarely past the
  // radius).
  std::span<const std::uint32_t> reached() const noexcept { return reached_; }
  // A vertex's distance along the surface from the last compute(); +infinity beyond the radius.
  float distance_mm(std::uint32_t vertex) const noexcept;
  // The triangles around a vertex (indices of Mesh::indices / 3).
  std::span<const std::uint32_t> triangles_around(std::uint32_t vertex) const noexcept {
    return {vertex_triangles_.data() + first_triangle_[vertex],
            first_triangle_[vertex + 1] - first_triangle_[vertex]};
  }

 private:
  // The triangle beyond edge (p, q) of `triangle` (-1: none, or not an edge of it) and its third corner.
  struct Across {
    std::int32_t triangle;
    std::uint32_t corner;
  };
  Across across(std::uint32_t triangle, std::uint32_t p, std::uint32_t q) const;
  void update(std::uint32_t vertex, std::uint32_t triangle);
  void correct(float within_mm);
  float update_again(std::uint32_t vertex);
  float along_edges(std::uint32_t triangle, int k) const;
  // The update of the triangle's corner k (0-2) from the other two.
  // `unchecked`, where given, is set where the source could not be checked (see unless_a_false_source).
  float unfolded_update(std::uint32_t triangle, int k, bool* unchecked = nullptr) const;
  float unless_a_false_source(std::uint32_t triangle, int k, glm::vec2 source, glm::vec2 c2, float distance,
                              bool* unchecked) const;
  void push_or_lower(std::uint32_t vertex, float distance, bool along_edge);
  std::uint32_t pop();
  void sift_up(std::size_t at);
  void sift_down(std::size_t at);

  const Mesh& mesh_;
  std::vector<std::uint32_t> first_triangle_, vertex_triangles_;  // the triangles around each vertex
  // Corner k of triangle t laid out over the edge across from it: the next corner at the origin, the one
  // after at (edge_mm, 0), corner k at `corner` (y >= 0). Laid out once, so the march reads these instead
  // of taking square roots of the positions.
  struct Layout {
    float edge_mm;
    glm::vec2 corner;
  };
  std::vector<Layout> layout_;        // layout_[3t + k]
  std::vector<std::int32_t> across_;  // across_[3t + e]: the triangle beyond edge e (corners e, e+1) of t
  std::vector<float> distance_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::uint8_t> along_edge_;  // the vertex's distance came along an edge, not through a triangle
  std::vector<std::uint8_t> unchecked_;   // its source could not be checked: computed afresh by correct()
  std::vector<std::uint8_t> queued_;      // correct(): 1 next to a vertex it lowered, 2 in queue_ besides
  std::vector<std::uint32_t> queue_;
  std::vector<std::int32_t> heap_position_;  // -1: not in the heap
  std::vector<std::uint32_t> heap_, touched_, reached_;
};

}  // namespace palpate
