#pragma once
// Distances along a mesh's surface from a point on it, out to a radius: the falloff of a dent measured
// over the surface, so that a press on one bank of a sulcus leaves the facing bank alone (the paper's
// named limit of its Euclidean falloff).
//
// Near the contact, exact: the shortest paths over the polyhedral surface by window propagation (Chen
// and Han, 1990, with Xin and Wang's 2009 filtering). A window is an interval of an edge lit from one
// (pseudo-)source unfolded into the edge's plane; windows cross triangles about nearest first, split at
// the vertices they light, and bend only at saddle and boundary vertices, which become pseudo-sources
// lighting only the triangles a shortest path can turn into. The parts of a window that a vertex's known
// path reaches sooner are trimmed away. Their number grows faster than the area, so in a dent's tail,
// where the weight changes slowly, fast marching takes over from the exact values (Kimmel and Sethian,
// 1998): the front crosses each triangle from the virtual point source that its two known corners place
// in its plane; at an obtuse corner the neighbouring triangle is unfolded into the plane. A triangle whose
// corners the front reached from either side of a saddle vertex or a fold (its source proves false) is
// crossed through its neighbour instead, and once all are known, a vertex the front still reached along
// an edge is updated again. Written here: no Debian library computes paths on a triangle mesh out to a
// radius with a workspace reused per frame (CGAL's exact shortest paths serve as the tests' reference:
// exact, but they sequence the whole mesh, seconds per source).
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

  // How far each part reaches: exact within `exact_mm`, or as far as the first `window_budget` windows
  // reach (a bound on the cost, as their number grows faster than the area); beyond, fast marching, a few
  // percent long at most. The second look after the march (which puts right the vertices the front
  // reached along an edge, and those after them) stops at `second_look_mm` but for the neighbours of a
  // vertex it changed by over 1%: beyond it a distance may stay a few percent long, as in a dent's tail
  // where that no longer matters. By default exact throughout.
  struct Reach {
    float exact_mm = std::numeric_limits<float>::infinity();
    std::size_t window_budget = std::numeric_limits<std::size_t>::max();
    float second_look_mm = std::numeric_limits<float>::infinity();
  };
  // The distances from `point_mm` (on triangle `triangle`, the t-th of Mesh::indices / 3) out to
  // `radius_mm`. Allocates only while it lights more windows than any compute before it or reserve()
  // made room for. Throws palpate::Error for a triangle out of range.
  void compute(std::uint32_t triangle, glm::vec3 point_mm, float radius_mm, Reach reach);
  // Exact throughout.
  void compute(std::uint32_t triangle, glm::vec3 point_mm, float radius_mm);
  // Room for the windows of a compute() with this budget (a window's children and a pseudo-source's
  // windows past it too), so that it allocates nothing.
  void reserve(std::size_t window_budget) { windows_.reserve(window_budget + budget_overrun); }
  static constexpr std::size_t budget_overrun = 64;

  // The vertices within the radius, from the last compute(), nearest first (but for those the second
  // look moved by a few percent beyond `exact_mm`, rarely past the radius).
  std::span<const std::uint32_t> reached() const noexcept { return reached_; }
  // How many windows the last compute() lit (up to budget_overrun more than its budget).
  std::size_t windows() const noexcept { return windows_.size(); }
  // A vertex's distance along the surface from the last compute(); +infinity beyond the radius.
  float distance_mm(std::uint32_t vertex) const noexcept;
  // The triangles around a vertex (indices of Mesh::indices / 3).
  std::span<const std::uint32_t> triangles_around(std::uint32_t vertex) const noexcept {
    return {vertex_triangles_.data() + first_triangle_[vertex],
            first_triangle_[vertex + 1] - first_triangle_[vertex]};
  }

 private:
  // An interval [b0, b1] of edge `edge` (corners edge, edge + 1) of `triangle`, lit from the source at
  // (sx, -sy) in the edge's frame (its first corner at the origin, its second at (length, 0), the
  // triangle's third corner above), sigma along the surface from the contact: the window lights
  // `triangle`.
  // A pseudo-source waiting to light its triangles is one too: `source` the vertex, sigma its distance,
  // `edge` pseudo_source_event.
  struct Window {
    double b0, b1, sx, sy, sigma;
    std::uint32_t triangle;
    std::uint32_t source;  // the pseudo-source vertex; no_vertex for the contact point
    std::uint32_t next;    // the next in its bucket
    std::uint8_t edge;
  };
  void enqueue(const Window& window, double key);
  void light(std::uint32_t triangle, glm::vec3 point_mm);
  void emit(std::uint32_t vertex, double sigma);
  void leave(std::uint32_t triangle, int edge, double b0, double b1, glm::dvec2 source, double sigma,
             std::uint32_t from);
  bool trim(Window& window) const noexcept;
  void propagate(const Window& window);
  void lower(std::uint32_t vertex, float distance, float arrival);
  // The triangle beyond edge (p, q) of `triangle` (-1: none, or not an edge of it) and its third corner.
  struct Across {
    std::int32_t triangle;
    std::uint32_t corner;
    float from_p_mm, from_q_mm;  // the corner's edges to p and q
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
  // What the windows and the march read of a triangle, in one cache line.
  struct alignas(64) Triangle {
    std::uint32_t corner[3];      // Mesh::indices
    std::int32_t across[3];       // the triangle beyond edge e (corners e, e + 1); -1: none
    std::uint8_t across_edge[3];  // which edge of that triangle it is
    Layout layout[3];
  };
  static_assert(sizeof(Triangle) == 64);
  std::vector<Triangle> triangle_;
  std::vector<float> corner_angle_, fan_start_;  // [3t + k]: the corner's angle; where it starts round it
  std::vector<float> fan_angle_;  // each vertex's corners' angles; NaN: its triangles do not close round it
  std::vector<Window> windows_;
  // The windows waiting, in buckets of their nearest distance to the contact: taken nearest bucket
  // first, each bucket last in, first out. Any order gives the exact paths (every filter compares with the
  // length of a real path); near the order of distance, the filters find the vertices' distances known.
  std::vector<std::uint32_t> buckets_;
  std::size_t bucket_ = 0;
  float exact_mm_ = 0.0f;
  std::size_t window_budget_ = 0;
  // Each vertex's state in one record, so that a look at a vertex reads one cache line, not one per array
  // (the windows and the march visit a patch's vertices in no order the arrays could follow).
  struct VertexState {
    float distance = std::numeric_limits<float>::infinity();
    float arrival = 0.0f;  // where the path to a pseudo-source arrives, as an angle round it (NaN: unknown)
    std::int32_t heap_position = -1;  // -1: not in the heap
    bool alive : 1 = false;
    bool exact : 1 = false;          // within exact_mm: the march leaves it as the windows found it
    bool along_edge : 1 = false;     // its distance came along an edge, not through a triangle
    bool unchecked : 1 = false;      // its source could not be checked: computed afresh by correct()
    std::uint8_t queued : 2 = 0;     // correct(): 1 next to a vertex it lowered, 2 in queue_ besides
    bool pseudo_source : 1 = false;  // a saddle (corners' angles over 2 pi) or on a boundary; kept
  };
  static_assert(sizeof(VertexState) == 16);
  std::vector<VertexState> vertex_;
  std::vector<std::uint32_t> queue_;
  std::vector<std::uint32_t> heap_, touched_, reached_;
};

}  // namespace palpate
