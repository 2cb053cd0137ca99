// Bvh queries: segment cast and closest point, iterative with a fixed stack, no allocation.
#include "palpate/core/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <limits>

namespace palpate {
namespace {

constexpr float no_entry = std::numeric_limits<float>::infinity();

glm::dvec3 vertex(const Bvh::Triangle& tri, int k) noexcept {
  return glm::dvec3(tri.vertices[std::size_t(k)]);
}

// Where the segment (origin, 1 / direction) enters the box, in segment parameter, or no_entry when it
// misses it or enters after t_max.
[[gnu::always_inline]] inline float entry(const Bvh::Node& node, const glm::vec3& origin,
                                          const glm::vec3& inverse, float t_max) noexcept {
  const float x1 = (node.min.x - origin.x) * inverse.x, x2 = (node.max.x - origin.x) * inverse.x;
  const float y1 = (node.min.y - origin.y) * inverse.y, y2 = (node.max.y - origin.y) * inverse.y;
  const float z1 = (node.min.z - origin.z) * inverse.z, z2 = (node.max.z - origin.z) * inverse.z;
  const float t_in = std::max(std::max(std::min(x1, x2), std::min(y1, y2)), std::max(std::min(z1, z2), 0.0f));
  const float t_out =
      std::min(std::min(std::max(x1, x2), std::max(y1, y2)), std::min(std::max(z1, z2), t_max));
  return t_in <= t_out ? t_in : no_entry;
}

// Segment from `from` along `d` against one triangle, in double. The edge values are signed volumes
// det(d, p, q) of the vertices relative to `from`; a shared edge gives its two triangles exactly
// opposite values, so no segment slips between them. Values within their rounding error count as zero
// (the triangle is inflated by ~1e-16 of its size), which also closes the gaps at shared vertices.
[[gnu::always_inline]] inline bool cross_triangle(const Bvh::Triangle& tri, const glm::dvec3& from,
                                                  const glm::dvec3& d, Faces faces, double start_tolerance,
                                                  double& t) noexcept {
  const glm::dvec3 v0 = vertex(tri, 0), v1 = vertex(tri, 1), v2 = vertex(tri, 2);
  const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
  const glm::dvec3 a = v0 - from;
  const double dn = glm::dot(n, d);
  const double start = -glm::dot(n, a);  // signed distance of `from` to the plane, times |n|
  // The cheap plane tests first: most triangles near a short segment are not reached at all.
  const bool front = dn < 0.0;
  if (front) {
    if (start + dn > 0.0) return false;  // ends in front of the plane
    if (start < 0.0 && start * start > start_tolerance * start_tolerance * glm::dot(n, n)) return false;
  } else {
    if (dn == 0.0 || faces == Faces::front || start + dn < 0.0) return false;
    if (start > 0.0 && start * start > start_tolerance * start_tolerance * glm::dot(n, n)) return false;
  }
  const glm::dvec3 b = v1 - from, c = v2 - from;
  const double u = glm::dot(d, glm::cross(b, c));
  const double v = glm::dot(d, glm::cross(c, a));
  const double w = glm::dot(d, glm::cross(a, b));
  const glm::dvec3 extent = glm::max(glm::max(glm::abs(a), glm::abs(b)), glm::abs(c));
  const double reach = std::max(std::max(extent.x, extent.y), extent.z);
  const glm::dvec3 abs_d = glm::abs(d);
  const double zero = 1e-14 * std::max(std::max(abs_d.x, abs_d.y), abs_d.z) * reach * reach;
  if (front ? (u > zero || v > zero || w > zero) : (u < -zero || v < -zero || w < -zero)) return false;
  t = std::clamp(start / -dn, 0.0, 1.0);
  return true;
}

[[gnu::always_inline]] inline float box_distance2(const Bvh::Node& node, const glm::vec3& p) noexcept {
  const glm::vec3 outside = glm::max(glm::max(node.min - p, p - node.max), glm::vec3(0.0f));
  return glm::dot(outside, outside);
}

// Walks the Voronoi regions of the vertices, the edges and the face. Naming the feature is compiled in
// only where asked for: the faces-near query calls this for every triangle it tests.
template <bool named>
glm::dvec3 closest_point_in_region(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                   const glm::dvec3& c, TriangleFeature* feature) noexcept {
  const auto name = [feature](TriangleFeature f) {
    if constexpr (named) *feature = f;
  };
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    name(TriangleFeature::a);
    return a;
  }
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) {
    name(TriangleFeature::b);
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    name(TriangleFeature::ab);
    return a + ab * (d1 / (d1 - d3));
  }
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) {
    name(TriangleFeature::c);
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    name(TriangleFeature::ac);
    return a + ac * (d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    name(TriangleFeature::bc);
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denominator = va + vb + vc;
  // A degenerate (zero-area) triangle: any vertex is as good.
  if (denominator <= 0.0) {
    name(TriangleFeature::a);
    return a;
  }
  name(TriangleFeature::face);
  return a + ab * (vb / denominator) + ac * (vc / denominator);
}

}  // namespace

glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) noexcept {
  return closest_point_in_region<false>(p, a, b, c, nullptr);
}

glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c, TriangleFeature& feature) noexcept {
  return closest_point_in_region<true>(p, a, b, c, &feature);
}

std::size_t Bvh::memory_bytes() const noexcept {
  return nodes_.capacity() * sizeof(Node) + triangles_.capacity() * sizeof(Triangle) +
         objects_.capacity() * sizeof(ObjectRange);
}

std::array<std::span<const std::byte>, 3> Bvh::memory() const noexcept {
  return {std::as_bytes(std::span(nodes_)), std::as_bytes(std::span(triangles_)),
          std::as_bytes(std::span(objects_))};
}

Bounds Bvh::bounds() const noexcept {
  if (nodes_.empty()) return {};
  return {nodes_[0].min, nodes_[0].max};
}

bool Bvh::contains(int object) const noexcept {
  return std::any_of(objects_.begin(), objects_.end(),
                     [object](const ObjectRange& r) { return r.object == object; });
}

Bvh::Location Bvh::locate(std::uint32_t primitive) const noexcept {
  const std::uint32_t id = triangles_[primitive].id;
  const auto range =
      std::upper_bound(objects_.begin(), objects_.end(), id,
                       [](std::uint32_t value, const ObjectRange& r) { return value < r.first_id; }) -
      1;
  return {range->object, int(id - range->first_id)};
}

BvhHit Bvh::make_hit(std::uint32_t primitive, const glm::dvec3& point) const noexcept {
  BvhHit hit;
  const Location location = locate(primitive);
  hit.object = location.object;
  hit.triangle = location.triangle;
  hit.primitive = primitive;
  hit.point_mm = glm::vec3(point);
  const Triangle& tri = triangles_[primitive];
  const glm::dvec3 n = glm::cross(vertex(tri, 1) - vertex(tri, 0), vertex(tri, 2) - vertex(tri, 0));
  const double length = glm::length(n);
  hit.normal = length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f);
  return hit;
}

bool Bvh::Neighbourhood::covers(const glm::dvec3& point) const noexcept {
  return count > 0 && glm::all(glm::greaterThanEqual(point, glm::dvec3(low) + inner_margin_mm)) &&
         glm::all(glm::lessThanEqual(point, glm::dvec3(high) - inner_margin_mm));
}

bool Bvh::gather(Neighbourhood& near, glm::vec3 low, glm::vec3 high) const noexcept {
  near.count = 0;
  near.low = low;
  near.high = high;
  near.gathered_from = nodes_.data();
  if (nodes_.empty() || !boxes_meet(nodes_[0].min, nodes_[0].max, low, high)) return false;
  // Both children are tested before either is entered (as in first_hit): the box meets one of them at
  // most levels, and a node is then read only when it is entered.
  std::uint32_t stack[max_depth];
  std::size_t top = 0;
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count > 0) {
      if (near.count == Neighbourhood::capacity) {
        near.count = 0;
        return false;
      }
      const auto k = std::size_t(near.count++);
      near.first[k] = node.first;
      near.size[k] = node.count;
      for (int a = 0; a < 3; ++a) {
        near.min[std::size_t(a)][k] = node.min[a];
        near.max[std::size_t(a)][k] = node.max[a];
      }
    } else {
      const bool left = boxes_meet(nodes_[node.first].min, nodes_[node.first].max, low, high);
      const bool right = boxes_meet(nodes_[node.first + 1].min, nodes_[node.first + 1].max, low, high);
      if (left || right) {
        if (left && right) stack[top++] = node.first + 1;
        current = left ? node.first : node.first + 1;
        continue;
      }
    }
    if (top == 0) break;
    current = stack[--top];
  }
  return near.count > 0;
}

void Bvh::prefetch(const Neighbourhood& near) const noexcept {
  if (!gathered_here(near)) return;
  constexpr std::uintptr_t line = 64;
  for (int k = 0; k < near.count; ++k) {
    const auto from = reinterpret_cast<std::uintptr_t>(&triangles_[near.first[std::size_t(k)]]);
    const std::uintptr_t to = from + near.size[std::size_t(k)] * sizeof(Triangle);
    for (std::uintptr_t at = from & ~(line - 1); at < to; at += line)
      __builtin_prefetch(reinterpret_cast<const void*>(at));
  }
}

BvhHit Bvh::first_hit(const glm::dvec3& from, const glm::dvec3& to, Faces faces, double start_tolerance_mm,
                      ObjectMask seen, const Neighbourhood* near) const noexcept {
  if (nodes_.empty()) return {};
  const glm::dvec3 d = to - from;
  const glm::vec3 origin(from);
  glm::vec3 inverse;
  for (int a = 0; a < 3; ++a) {
    const float component = float(d[a]);
    // A zero component becomes a tiny one of the same sign: the slab test then never sees 0 * inf.
    inverse[a] = 1.0f / (component != 0.0f ? component : std::copysign(1e-30f, component));
  }
  double best_t = 2.0;  // above any segment parameter
  std::uint32_t best = 0;
  // Every subtree the segment enters before the best hit so far, nearer child first; the farther waits
  // on the stack and is re-culled against the best hit when popped. Ties in t go to the lowest index,
  // so that the answer does not depend on the order of the search.
  const auto search_tree = [&] {
    std::uint32_t stack[max_depth];
    std::size_t top = 0;
    stack[top++] = 0;
    const auto reach = [&] { return float(std::min(best_t, 1.0)); };
    while (top > 0) {
      std::uint32_t current = stack[--top];
      if (entry(nodes_[current], origin, inverse, reach()) == no_entry) continue;
      for (;;) {
        const Node& node = nodes_[current];
        if (node.count > 0) {
          for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
            double t;
            if (cross_triangle(triangles_[i], from, d, faces, start_tolerance_mm, t) &&
                (t < best_t || (t == best_t && i < best)) && primitive_seen(seen, i)) {
              best_t = t;
              best = i;
            }
          }
          break;
        }
        const float left = entry(nodes_[node.first], origin, inverse, reach());
        const float right = entry(nodes_[node.first + 1], origin, inverse, reach());
        if (left != no_entry && right != no_entry) {
          const bool left_first = left <= right;
          stack[top++] = left_first ? node.first + 1 : node.first;
          current = left_first ? node.first : node.first + 1;
        } else if (left != no_entry) {
          current = node.first;
        } else if (right != no_entry) {
          current = node.first + 1;
        } else {
          break;
        }
      }
    }
  };
  // From inside the neighbourhood, the part of the segment within it is searched among its leaves
  // alone (they hold every triangle that part can meet); a hit there is the first hit. Otherwise, or
  // when that part is clear, from the root.
  if (near != nullptr && gathered_here(*near) && near->covers(from)) {
    const glm::dvec3 low = glm::dvec3(near->low) + Neighbourhood::inner_margin_mm,
                     high = glm::dvec3(near->high) - Neighbourhood::inner_margin_mm;
    double limit = 1.0;
    for (int a = 0; a < 3; ++a) {
      if (d[a] > 0.0) limit = std::min(limit, (high[a] - from[a]) / d[a]);
      if (d[a] < 0.0) limit = std::min(limit, (low[a] - from[a]) / d[a]);
    }
    // The slab tests of all the leaves first, with no branch between them, then the triangles of the
    // few whose bounds the segment enters.
    const auto& min = near->min;
    const auto& max = near->max;
    const float reach = float(limit);
    bool entered[Neighbourhood::capacity];
    for (std::size_t k = 0; k < std::size_t(near->count); ++k) {
      const float x1 = (min[0][k] - origin.x) * inverse.x, x2 = (max[0][k] - origin.x) * inverse.x;
      const float y1 = (min[1][k] - origin.y) * inverse.y, y2 = (max[1][k] - origin.y) * inverse.y;
      const float z1 = (min[2][k] - origin.z) * inverse.z, z2 = (max[2][k] - origin.z) * inverse.z;
      const float t_in =
          std::max(std::max(std::min(x1, x2), std::min(y1, y2)), std::max(std::min(z1, z2), 0.0f));
      const float t_out =
          std::min(std::min(std::max(x1, x2), std::max(y1, y2)), std::min(std::max(z1, z2), reach));
      entered[k] = t_in <= t_out;
    }
    // The leaves are listed in index order, so the first of equal t found is the lowest index.
    for (std::size_t k = 0; k < std::size_t(near->count); ++k) {
      if (!entered[k]) continue;
      for (std::uint32_t i = near->first[k]; i < near->first[k] + near->size[k]; ++i) {
        double t;
        if (cross_triangle(triangles_[i], from, d, faces, start_tolerance_mm, t) && t < best_t &&
            primitive_seen(seen, i)) {
          best_t = t;
          best = i;
        }
      }
    }
    // A hit past the box, or none, leaves the rest of the segment to search from the root (up to that
    // hit): a triangle that is not listed may come first out there.
    if (best_t > limit && limit < 1.0) search_tree();
  } else {
    search_tree();
  }
  if (best_t > 1.0) return {};
  BvhHit hit = make_hit(best, from + d * best_t);
  hit.t = float(best_t);
  return hit;
}

BvhHit Bvh::first_hit_around(const glm::dvec3& from, const glm::dvec3& to, std::uint32_t primitive,
                             const glm::dvec3& vertex, double start_tolerance_mm,
                             ObjectMask seen) const noexcept {
  std::array<std::uint32_t, 64> around;
  const std::size_t count = faces_around(primitive, vertex, around);
  const glm::dvec3 d = to - from;
  double best_t = 2.0;  // above any segment parameter
  std::uint32_t best = 0;
  for (std::size_t i = 0; i < count; ++i) {
    double t;
    if (cross_triangle(triangles_[around[i]], from, d, Faces::front, start_tolerance_mm, t) &&
        (t < best_t || (t == best_t && around[i] < best)) && primitive_seen(seen, around[i])) {
      best_t = t;
      best = around[i];
    }
  }
  if (best_t > 1.0) return {};
  BvhHit hit = make_hit(best, from + d * best_t);
  hit.t = float(best_t);
  return hit;
}

std::size_t Bvh::faces_around(std::uint32_t primitive, const glm::dvec3& vertex,
                              std::span<std::uint32_t> around) const noexcept {
  const auto& first = triangles_[primitive].vertices;
  int at = 0;
  while (at < 3 && glm::dvec3(first[std::size_t(at)]) != vertex) ++at;
  if (at == 3) return 0;
  const glm::vec3 centre = first[std::size_t(at)];
  std::uint32_t current = primitive;
  for (std::size_t count = 0; count < around.size(); ++count) {
    around[count] = current;
    current = neighbour(current, at);
    if (current == no_neighbour) return 0;
    if (current == primitive) return count + 1;
    const auto& corners = triangles_[current].vertices;
    at = corners[0] == centre ? 0 : corners[1] == centre ? 1 : 2;
  }
  return 0;
}

BvhHit Bvh::closest_point(const glm::dvec3& point, double max_distance_mm, ObjectMask seen) const noexcept {
  return closest_point_if<false>(point, max_distance_mm,
                                 [&](std::uint32_t primitive) { return primitive_seen(seen, primitive); });
}

BvhHit Bvh::closest_point_where(const glm::dvec3& point, double max_distance_mm,
                                const std::function<bool(std::uint32_t)>& accepted) const {
  return closest_point_if<true>(point, max_distance_mm, accepted);
}

template <bool ask_first, class Accepted>
BvhHit Bvh::closest_point_if(const glm::dvec3& point, double max_distance_mm,
                             const Accepted& accepted) const noexcept {
  if (nodes_.empty() || !(max_distance_mm >= 0.0)) return {};
  const glm::vec3 p(point);
  double best_d2 = max_distance_mm * max_distance_mm;
  glm::dvec3 best_point(0.0);
  std::uint32_t best = 0;
  bool found_any = false;
  // Box distances are in float: compare against a slightly enlarged bound so rounding never prunes.
  const auto bound = [&best_d2]() { return float(best_d2) * 1.0001f + 1e-12f; };
  std::uint32_t stack[max_depth];
  std::size_t top = 0;
  if (box_distance2(nodes_[0], p) > bound()) return {};
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        if constexpr (ask_first) {
          if (!accepted(i)) continue;
        }
        const Triangle& tri = triangles_[i];
        const glm::dvec3 q = closest_point_on_triangle(point, vertex(tri, 0), vertex(tri, 1), vertex(tri, 2));
        const glm::dvec3 offset = q - point;
        const double d2 = glm::dot(offset, offset);
        if (d2 <= best_d2 && (ask_first || accepted(i))) {
          best_d2 = d2;
          best_point = q;
          best = i;
          found_any = true;
        }
      }
    } else {
      const float left = box_distance2(nodes_[node.first], p);
      const float right = box_distance2(nodes_[node.first + 1], p);
      const bool left_in = left <= bound(), right_in = right <= bound();
      if (left_in && right_in) {
        const bool left_first = left <= right;
        stack[top++] = left_first ? node.first + 1 : node.first;
        current = left_first ? node.first : node.first + 1;
        continue;
      }
      if (left_in || right_in) {
        current = left_in ? node.first : node.first + 1;
        continue;
      }
    }
    bool found = false;
    while (top > 0) {
      current = stack[--top];
      if (box_distance2(nodes_[current], p) <= bound()) {
        found = true;
        break;
      }
    }
    if (!found) break;
  }
  if (!found_any) return {};
  BvhHit hit = make_hit(best, best_point);
  hit.distance_mm = float(std::sqrt(best_d2));
  return hit;
}

BvhHit Bvh::closest_point_near(const glm::dvec3& point, const glm::dvec3& around, double radius_mm,
                               ObjectMask seen, const Neighbourhood* near,
                               std::array<std::uint32_t, 2> left_out) const noexcept {
  if (nodes_.empty() || !(radius_mm >= 0.0)) return {};
  const glm::vec3 centre(around);
  // Box distances are in float: compare against a slightly enlarged bound so rounding never prunes.
  const float reach2 = float(radius_mm * radius_mm) * 1.0001f + 1e-12f;
  double best_d2 = std::numeric_limits<double>::infinity();
  glm::dvec3 best_point(0.0);
  std::uint32_t best = 0;
  const auto consider = [&](std::uint32_t i) {
    if (i == left_out[0] || i == left_out[1]) return;
    const Triangle& tri = triangles_[i];
    const glm::dvec3 a = vertex(tri, 0), b = vertex(tri, 1), c = vertex(tri, 2);
    // Its bounds first (in double, exact): most of a leaf's triangles are out of reach.
    const glm::dvec3 outside =
        glm::max(glm::max(glm::min(glm::min(a, b), c) - around, around - glm::max(glm::max(a, b), c)), 0.0);
    if (glm::dot(outside, outside) > radius_mm * radius_mm) return;
    const glm::dvec3 touch = closest_point_on_triangle(around, a, b, c) - around;
    if (glm::dot(touch, touch) > radius_mm * radius_mm) return;
    const glm::dvec3 q = closest_point_on_triangle(point, a, b, c);
    const double d2 = glm::dot(q - point, q - point);
    // Ties go to the lowest index, so the answer does not depend on the order of the search.
    if ((d2 < best_d2 || (d2 == best_d2 && i < best)) && primitive_seen(seen, i)) {
      best_d2 = d2;
      best_point = q;
      best = i;
    }
  };
  // The ball inside the neighbourhood: its leaves hold every triangle that can reach it.
  if (near != nullptr && gathered_here(*near) && near->covers(around - radius_mm) &&
      near->covers(around + radius_mm)) {
    // The leaves' distances first, with no branch between them, then the triangles of the few in reach.
    const auto& min = near->min;
    const auto& max = near->max;
    bool in_reach[Neighbourhood::capacity];
    for (std::size_t k = 0; k < std::size_t(near->count); ++k) {
      const float x = std::max(std::max(min[0][k] - centre.x, centre.x - max[0][k]), 0.0f);
      const float y = std::max(std::max(min[1][k] - centre.y, centre.y - max[1][k]), 0.0f);
      const float z = std::max(std::max(min[2][k] - centre.z, centre.z - max[2][k]), 0.0f);
      in_reach[k] = x * x + y * y + z * z <= reach2;
    }
    for (std::size_t k = 0; k < std::size_t(near->count); ++k) {
      if (!in_reach[k]) continue;
      for (std::uint32_t i = near->first[k]; i < near->first[k] + near->size[k]; ++i) consider(i);
    }
  } else {
    std::uint32_t stack[max_depth + 1];  // one sibling waits per level, plus the node popped next
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (box_distance2(node, centre) > reach2) continue;
      if (node.count == 0) {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
        continue;
      }
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) consider(i);
    }
  }
  if (!std::isfinite(best_d2)) return {};
  BvhHit hit = make_hit(best, best_point);
  hit.distance_mm = float(std::sqrt(best_d2));
  return hit;
}

}  // namespace palpate
