#pragma once
// A bounding volume hierarchy over the world-space triangles of a scene's touchable objects, built
// once at load. Written by hand because it is the product: the haptic tick's cost is its query cost,
// and a general-purpose library tree (pointer nodes, virtual callbacks, allocation per query) cannot
// give a bounded, allocation-free, cache-friendly query.
//
// Layout: one flat array of 32-byte nodes (two sibling children stored side by side, depth-first), and
// the triangles copied into leaf order, 56 bytes each (three float vertices, an id, the triangles
// across its edges, so that crossing an edge reads no other array, and the clear space above it), so a
// leaf's triangles are one contiguous read. Built top-down with a binned surface-area heuristic.
//
// build() allocates and may throw palpate::Error; every query is const, noexcept, allocation-free and
// safe in the haptic tick, and safe to run from several threads at once.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"

namespace palpate {

struct BvhHit {
  int object = -1;              // scene object index; -1 when nothing was hit
  int triangle = -1;            // triangle index in that object's mesh
  glm::vec3 point_mm{0.0f};     // the hit (or closest) point, world mm
  float t = 0.0f;               // first_hit: segment parameter in [0, 1]; closest_point: 0
  float distance_mm = 0.0f;     // closest_point: distance from the query point; first_hit: 0
  glm::vec3 normal{0.0f};       // the triangle's unit face normal, outward (counter-clockwise winding)
  std::uint32_t primitive = 0;  // the triangle's index in the BVH (see Bvh::triangle)

  bool hit() const noexcept { return object >= 0; }
};

// Which side of a triangle a segment may enter through to count as a hit.
enum class Faces {
  front,  // only from outside to inside (against the outward normal): the haptic proxy's view
  both,   // either side
};

// Which scene objects a query sees, or a build includes: object i when i < size() and mask[i] != 0.
// An empty mask means every object. Queries check it only for a triangle that would be their answer,
// so a mask costs next to nothing.
using ObjectMask = std::span<const std::uint8_t>;
inline bool sees(ObjectMask mask, int object) noexcept {
  return mask.empty() || (object >= 0 && std::size_t(object) < mask.size() && mask[std::size_t(object)] != 0);
}

// The part of a triangle (a, b, c) a closest point lies on: a corner, an edge (inside it) or the face.
enum class TriangleFeature { a, b, c, ab, ac, bc, face };

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection, 5.1.5); a
// corner is returned bit for bit.
glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) noexcept;
// The same, with the part of the triangle it lies on.
glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c, TriangleFeature& feature) noexcept;

class Bvh {
 public:
  struct Node {           // 32 bytes
    glm::vec3 min;        // bounds, world mm, padded outward so float slab tests stay conservative
    std::uint32_t first;  // leaf: first triangle; interior: left child (the right child is first + 1)
    glm::vec3 max;
    std::uint32_t count;  // leaf: triangle count (> 0); interior: 0
  };
  struct Triangle {                       // 56 bytes
    std::array<glm::vec3, 3> vertices;    // world mm, counter-clockwise seen from outside
    std::uint32_t id;                     // the scene-wide triangle number (objects in scene order)
    std::array<std::uint32_t, 3> across;  // the triangles across its edges: see neighbour()
    float clearance_mm;                   // how high above it no other triangle comes: see clear_above()

    float longest_edge_mm() const noexcept {
      return std::max({glm::distance(vertices[0], vertices[1]), glm::distance(vertices[1], vertices[2]),
                       glm::distance(vertices[2], vertices[0])});
    }
  };

  // Deepest possible leaf (the build splits at the median below depth 48): the queries' stack size.
  static constexpr std::size_t max_depth = 96;

  Bvh() = default;

  // World-space triangles of the scene's touchable objects (object transform applied). Throws
  // palpate::Error naming the object when a mesh has out-of-range indices or non-finite positions.
  static Bvh build(const Scene& scene);
  // The same over the objects `included` names, touchable or not (an empty mask: all of them): a tree
  // over one object for aiming at it, or over every object so that a HapticLoop can make an object
  // touchable while it runs (its queries then see only the touchable ones through a mask).
  static Bvh build(const Scene& scene, ObjectMask included);

  std::size_t triangle_count() const noexcept { return triangles_.size(); }
  // Whether the tree holds triangles of scene object `object`.
  bool contains(int object) const noexcept;
  std::size_t node_count() const noexcept { return nodes_.size(); }
  // Bytes held by the nodes, the triangles and the object table.
  std::size_t memory_bytes() const noexcept;
  // Those arrays, for a caller that locks them in memory (HapticLoop does).
  std::array<std::span<const std::byte>, 3> memory() const noexcept;
  // The padded bounds of everything; zero for an empty tree.
  Bounds bounds() const noexcept;
  // The median longest edge of an even sample of the triangles (0 for an empty tree): the scale of the
  // mesh where a point has no face of its own to measure, such as a proxy in free space.
  float typical_triangle_size_mm() const noexcept { return typical_triangle_size_mm_; }

  // The leaves whose bounds meet a box, listed flat with their bounds: where a query that stays in the
  // box looks instead of walking the tree from the root (the haptic proxy keeps one around itself,
  // gathered again between ticks as it moves: proxy_prepare). A cast then tests a dozen or so boxes
  // side by side instead of a chain of 18 dependent ones. Fixed size, no allocation.
  struct Neighbourhood {
    static constexpr int capacity = 48;
    // Queries trust it only this far inside the box, so that rounding at its faces never matters.
    static constexpr double inner_margin_mm = 1e-3;
    glm::vec3 low{0.0f}, high{0.0f};      // the box, world mm
    int count = 0;                        // 0: none gathered
    const void* gathered_from = nullptr;  // the tree's nodes: another tree's queries ignore it
    // Leaf k holds the triangles first[k] to first[k] + size[k] - 1 (a copy: no node is read again).
    std::array<std::uint32_t, capacity> first{}, size{};
    // The leaves' bounds, one array per coordinate, so that the tests of neighbouring leaves run side by
    // side.
    std::array<std::array<float, capacity>, 3> min{}, max{};

    // Whether `point` lies in the box (less the margin).
    bool covers(const glm::dvec3& point) const noexcept;
  };
  // Gathers the neighbourhood of the box [low, high]. False, and an empty neighbourhood (that
  // remembers its box), when the box meets no leaf or more than Neighbourhood::capacity.
  bool gather(Neighbourhood& near, glm::vec3 low, glm::vec3 high) const noexcept;
  // Whether `near` was gathered from this tree: another tree's node indices mean nothing here.
  bool gathered_here(const Neighbourhood& near) const noexcept { return near.gathered_from == nodes_.data(); }
  // Asks the memory system for the triangles of `near`'s leaves without waiting for them, so that the
  // queries that follow find them in cache: for the time between ticks (proxy_prepare), where a read
  // from memory costs the tick nothing.
  void prefetch(const Neighbourhood& near) const noexcept;

  // The first triangle the segment from -> to crosses (smallest t; the lowest BVH index among equal
  // t), or no hit. Computed in double with a watertight edge test, so a segment through a shared edge
  // or vertex of a closed mesh always hits one of its triangles. A front-face crossing counts when
  // `from` is in front of the triangle's plane or at most `start_tolerance_mm` behind it (t is then 0),
  // and `to` is on or behind the plane. Only the objects `seen` names count. Given a neighbourhood that
  // covers `from`, the part of the segment inside it is searched among its leaves: the same answer,
  // sooner.
  BvhHit first_hit(const glm::dvec3& from, const glm::dvec3& to, Faces faces = Faces::front,
                   double start_tolerance_mm = 0.0, ObjectMask seen = {},
                   const Neighbourhood* near = nullptr) const noexcept;

  // Whether the segment from -> to lies in the space above triangle `primitive` that no other triangle
  // of the tree enters, so that no cast along it can hit anything: the proxy's walks over its own face
  // then need none. That space, measured at build, rises from a millionth of the triangle's longest
  // edge above its plane up to `clearance_mm` (at most a tenth of that edge, less over a sharp corner),
  // between sides slanted 45 degrees outward from its edges: a proxy handed over an edge from a face
  // bent down by less than 45 degrees starts inside it, and faces folded up beyond an edge by less than
  // 45 degrees stay outside it. False whenever in doubt (within a ten-millionth of that edge of the
  // space's bounds).
  bool clear_above(std::uint32_t primitive, const glm::dvec3& from, const glm::dvec3& to) const noexcept;

  // The first of the triangles around the corner of triangle `primitive` at `vertex` that the segment
  // crosses (tested as first_hit tests them; ties to the lowest index), found by going round the vertex
  // through neighbour() instead of searching the tree: for a look from just above a vertex, which meets
  // one of them first unless another surface passes within the segment's first few micrometres. No hit
  // when no corner of the triangle is at `vertex` (bit for bit), when none is crossed, when the
  // triangles do not close around the vertex (a border, a split vertex) or when more than 64 meet there.
  BvhHit first_hit_around(const glm::dvec3& from, const glm::dvec3& to, std::uint32_t primitive,
                          const glm::dvec3& vertex, double start_tolerance_mm = 0.0,
                          ObjectMask seen = {}) const noexcept;

  // The triangles around the corner of triangle `primitive` at `vertex`, in order round it (each one
  // across the edge from the vertex to the next corner of the one before), `primitive` first, written to
  // `around`; their number, or 0 when no corner of the triangle is at `vertex` (bit for bit), when they do
  // not close around it or when more than around.size() meet there.
  std::size_t faces_around(std::uint32_t primitive, const glm::dvec3& vertex,
                           std::span<std::uint32_t> around) const noexcept;

  // The closest point on any triangle of the `seen` objects to `point` no farther than
  // `max_distance_mm`, or no hit.
  BvhHit closest_point(const glm::dvec3& point, double max_distance_mm, ObjectMask seen = {}) const noexcept;
  // The same among the triangles `accepted` takes (by BVH index), asked before a triangle's distance: for
  // searches that leave out the triangles nearest the point, such as its own rings (not per tick: it
  // calls through a function).
  BvhHit closest_point_where(const glm::dvec3& point, double max_distance_mm,
                             const std::function<bool(std::uint32_t primitive)>& accepted) const;

  // Among the triangles of the `seen` objects that pass within `radius_mm` of `around`, the point
  // nearest `point`, or no hit: what a proxy resting at `around` could reach by sliding onto one of the
  // faces it touches.
  // Given a neighbourhood that holds the ball, only its leaves are searched (the same answer: ties go
  // to the lowest BVH index). The triangles `left_out` names (BVH indices; no_neighbour for none) are
  // not searched: faces the caller knows to be no nearer, which would cost the most to test (they pass
  // through the ball).
  BvhHit closest_point_near(const glm::dvec3& point, const glm::dvec3& around, double radius_mm,
                            ObjectMask seen = {}, const Neighbourhood* near = nullptr,
                            std::array<std::uint32_t, 2> left_out = {no_neighbour,
                                                                     no_neighbour}) const noexcept;

  // Calls visit(primitive) for each triangle whose bounds meet the box [low, high] (world mm). No
  // allocation; for searches around a region rather than along a ray or from a point.
  template <class Visit>
  void for_each_in_box(glm::vec3 low, glm::vec3 high, Visit&& visit) const noexcept {
    if (nodes_.empty()) return;
    const auto meets = [&](glm::vec3 min, glm::vec3 max) { return boxes_meet(min, max, low, high); };
    std::uint32_t stack[max_depth];
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!meets(node.min, node.max)) continue;
      if (node.count == 0) {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
        continue;
      }
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const auto& corners = triangles_[i].vertices;
        if (meets(glm::min(glm::min(corners[0], corners[1]), corners[2]),
                  glm::max(glm::max(corners[0], corners[1]), corners[2])))
          visit(i);
      }
    }
  }

  // A triangle by its BVH index (BvhHit::primitive), for callers that need it in double precision.
  const Triangle& triangle(std::uint32_t primitive) const noexcept { return triangles_[primitive]; }
  // The triangle across edge `edge` (from vertices[edge] to vertices[(edge + 1) % 3]) of a triangle, by
  // BVH index: the one other triangle of its object that uses the same two vertices, in the opposite
  // order. no_neighbour where there is none or more than one (a border, a non-manifold or misoriented
  // edge, or vertices split by the mesh, as on flat-shaded faces).
  static constexpr std::uint32_t no_neighbour = 0xffffffffu;
  std::uint32_t neighbour(std::uint32_t primitive, int edge) const noexcept {
    return triangles_[primitive].across[std::size_t(edge)];
  }
  // Where a BVH triangle comes from in the scene.
  struct Location {
    int object = -1;    // scene object index
    int triangle = -1;  // triangle index in that object's mesh
  };
  Location locate(std::uint32_t primitive) const noexcept;
  // Whether `seen` sees the object of a BVH triangle.
  bool primitive_seen(ObjectMask seen, std::uint32_t primitive) const noexcept {
    return seen.empty() || sees(seen, locate(primitive).object);
  }

  const std::vector<Node>& nodes() const noexcept { return nodes_; }

 private:
  // Whether the boxes [min, max] and [low, high] share a point (touching counts).
  static bool boxes_meet(glm::vec3 min, glm::vec3 max, glm::vec3 low, glm::vec3 high) noexcept {
    return min.x <= high.x && low.x <= max.x && min.y <= high.y && low.y <= max.y && min.z <= high.z &&
           low.z <= max.z;
  }

  struct ObjectRange {
    std::uint32_t first_id;  // scene-wide number of the object's first triangle
    int object;              // its index in the scene
  };

  BvhHit make_hit(std::uint32_t primitive, const glm::dvec3& point) const noexcept;
  // Fills each triangle's clearance_mm (bvh_clearance.cpp).
  void measure_clearances();
  template <bool ask_first, class Accepted>
  BvhHit closest_point_if(const glm::dvec3& point, double max_distance_mm,
                          const Accepted& accepted) const noexcept;

  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;
  std::vector<ObjectRange> objects_;  // touchable objects with triangles, by first_id
  float typical_triangle_size_mm_ = 0.0f;
};

}  // namespace palpate
