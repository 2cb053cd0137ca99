// The space above each triangle that no other triangle enters (Bvh::clear_above): measured once at
// build, because only the whole tree knows whether another sheet of the surface, a fold or a thin wall
// passes close above a face, and asked in the haptic tick, where it spares the proxy's walks over its
// own face their casts (most of a sliding tick's casts on a fine mesh).
#include <algorithm>
#include <array>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>
#include <vector>

#include "palpate/core/bvh.hpp"

namespace palpate {
namespace {

// The space's floor and ceiling and the query's margin, in shares of the triangle's longest edge: the
// floor lies below the height a proxy floats at (its default surface epsilon, 1 µm, on edges shorter
// than about a metre) and above the rounding of the neighbours' shared vertices; the ceiling lies
// above it on edges longer than about 10 µm; the margin is far above the rounding between build and
// tick.
constexpr double floor_share = 1e-6;
constexpr double ceiling_share = 0.1;
constexpr double margin_share = 1e-7;

// A triangle's plane and the sides of the space above it (each edge's outward normal in the plane; the
// side slants 45 degrees outward, so a point is inside it while its distance beyond the edge's line is
// at most its height), in double.
struct Frame {
  glm::dvec3 origin{0.0}, normal{0.0};
  std::array<glm::dvec3, 3> corner{}, outward{};
  double longest = 0.0;  // 0 for a zero-area triangle

  // False for a zero-area triangle: no space above it is trusted.
  bool valid() const noexcept { return longest > 0.0; }

  double height(const glm::dvec3& x) const noexcept { return glm::dot(normal, x - origin); }
  // Positive outside the slanted side of edge e.
  double beyond(int e, const glm::dvec3& x) const noexcept {
    return glm::dot(outward[std::size_t(e)], x - corner[std::size_t(e)]) - height(x);
  }
};

Frame frame_of(const Bvh::Triangle& tri) noexcept {
  Frame f;
  for (std::size_t e = 0; e < 3; ++e) f.corner[e] = glm::dvec3(tri.vertices[e]);
  f.origin = f.corner[0];
  const glm::dvec3 n = glm::cross(f.corner[1] - f.corner[0], f.corner[2] - f.corner[0]);
  const double twice_area = glm::length(n);
  if (!(twice_area > 0.0)) return f;
  f.normal = n / twice_area;
  for (std::size_t e = 0; e < 3; ++e) {
    const glm::dvec3 edge = f.corner[(e + 1) % 3] - f.corner[e];
    const double length = glm::length(edge);
    f.outward[e] = glm::cross(edge, f.normal) / length;  // |edge x normal| = |edge|: already unit
    f.longest = std::max(f.longest, length);
  }
  return f;
}

// The sine of half the triangle's sharpest corner: at height h the space reaches h over it beyond
// that corner. From the two sides' outward normals there: 1 + cos(pi - angle) = 2 sin^2(angle / 2).
double sharpest_corner(const Frame& f) noexcept {
  double sharpest = 1.0;
  for (std::size_t e = 0; e < 3; ++e) {
    const double cosine = glm::dot(f.outward[e], f.outward[(e + 2) % 3]);
    sharpest = std::min(sharpest, std::sqrt(std::max(0.0, 0.5 * (1.0 + cosine))));
  }
  return sharpest;
}

// The space's ceiling, a tenth of the longest edge, lower over a sharp corner so that the space reaches
// no more than a quarter of that edge beyond it; and how far the space reaches beyond the triangle in
// any coordinate: sideways the ceiling over the sharpest corner's half-angle sine, up the ceiling. No
// reach for a corner of no angle (no space).
struct Extent {
  double ceiling, reach;
};
Extent extent_of(const Frame& f) noexcept {
  const double sharpest = sharpest_corner(f);
  const double ceiling = f.longest * std::min(ceiling_share, 0.25 * sharpest);
  return {ceiling, sharpest > 0.0 ? ceiling / sharpest + ceiling : 0.0};
}

// The lowest height at which triangle `other` enters the space above `f` between `floor` and
// `ceiling`, or `ceiling` when it does not: the least height over the triangle clipped to the space
// (Sutherland-Hodgman: the space is the intersection of five half-spaces, and each clip adds at most
// one corner).
double lowest_inside(const Frame& f, const std::array<glm::dvec3, 3>& other, double floor,
                     double ceiling) noexcept {
  constexpr int planes = 5;  // under the floor, over the ceiling, beyond each side
  // The floor and the sides are measured half the query's margin inside, so that a triangle that only
  // touches them (a neighbour at its shared edge or corner, within rounding) is wholly outside.
  const double inset = 0.5 * margin_share * f.longest;
  const auto outside = [&](int k, const glm::dvec3& x) {
    if (k == 0) return floor + inset - f.height(x);
    if (k == 1) return f.height(x) - ceiling;
    return f.beyond(k - 2, x) + inset;
  };
  // Most triangles near a face lie wholly outside one of the five (below the floor, on a convex
  // surface; beyond a side, on a concave one): no clipping for those.
  for (int k = 0; k < planes; ++k) {
    bool all_outside = true;
    for (std::size_t i = 0; i < 3 && all_outside; ++i) all_outside = outside(k, other[i]) >= 0.0;
    if (all_outside) return ceiling;
  }
  std::array<glm::dvec3, 3 + planes> polygon, clipped;
  int size = 3;
  std::copy(other.begin(), other.end(), polygon.begin());
  for (int k = 0; k < planes && size > 0; ++k) {
    int kept = 0;
    for (int i = 0; i < size; ++i) {
      const glm::dvec3& a = polygon[std::size_t(i)];
      const glm::dvec3& b = polygon[std::size_t((i + 1) % size)];
      const double fa = outside(k, a), fb = outside(k, b);
      if (fa <= 0.0) clipped[std::size_t(kept++)] = a;
      if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0))
        clipped[std::size_t(kept++)] = a + (b - a) * (fa / (fa - fb));
    }
    polygon = clipped;
    size = kept;
  }
  double lowest = ceiling;
  for (int i = 0; i < size; ++i) lowest = std::min(lowest, f.height(polygon[std::size_t(i)]));
  return std::max(lowest, floor);
}

}  // namespace

void Bvh::measure_clearances() {
  // A few triangles at a time, neighbours in the tree's order: one search of the tree for the boxes
  // around them all, then each triangle against what it found (a search per triangle took most of the
  // time).
  constexpr std::size_t group = 8;
  struct Nearby {
    std::uint32_t primitive;
    glm::vec3 low, high;
    std::array<glm::dvec3, 3> corners;
  };
  std::vector<Nearby> nearby;
  for (std::size_t first = 0; first < triangles_.size(); first += group) {
    const std::size_t count = std::min(group, triangles_.size() - first);
    std::array<Frame, group> frames;
    std::array<double, group> ceilings;
    std::array<glm::vec3, group> lows, highs;
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (std::size_t k = 0; k < count; ++k) {
      const Triangle& tri = triangles_[first + k];
      frames[k] = frame_of(tri);
      const Extent extent = extent_of(frames[k]);
      ceilings[k] = extent.ceiling;
      const float reach = float(1.01 * extent.reach);  // a little more for rounding
      lows[k] = glm::min(glm::min(tri.vertices[0], tri.vertices[1]), tri.vertices[2]) - reach;
      highs[k] = glm::max(glm::max(tri.vertices[0], tri.vertices[1]), tri.vertices[2]) + reach;
      low = glm::min(low, lows[k]);
      high = glm::max(high, highs[k]);
    }
    nearby.clear();
    for_each_in_box(low, high, [&](std::uint32_t primitive) {
      const auto& v = triangles_[primitive].vertices;
      nearby.push_back({primitive,
                        glm::min(glm::min(v[0], v[1]), v[2]),
                        glm::max(glm::max(v[0], v[1]), v[2]),
                        {glm::dvec3(v[0]), glm::dvec3(v[1]), glm::dvec3(v[2])}});
    });
    for (std::size_t k = 0; k < count; ++k) {
      const Frame& f = frames[k];
      Triangle& tri = triangles_[first + k];
      tri.clearance_mm = 0.0f;
      if (!f.valid()) continue;
      const double floor = floor_share * f.longest;
      double clearance = ceilings[k];
      for (const Nearby& other : nearby) {
        if (other.primitive == first + k || !boxes_meet(other.low, other.high, lows[k], highs[k])) continue;
        clearance = lowest_inside(f, other.corners, floor, clearance);
        if (clearance <= floor) break;
      }
      // Rounded down, so that the stored height never claims more than was measured.
      float stored = float(clearance);
      if (double(stored) > clearance) stored = std::nextafter(stored, 0.0f);
      tri.clearance_mm = stored;
    }
  }
}

bool Bvh::clear_above(std::uint32_t primitive, const glm::dvec3& from, const glm::dvec3& to) const noexcept {
  const Triangle& tri = triangles_[primitive];
  const Frame f = frame_of(tri);
  if (!f.valid()) return false;
  const double margin = margin_share * f.longest;
  const double low = floor_share * f.longest + margin, high = double(tri.clearance_mm) - margin;
  for (const glm::dvec3* x : {&from, &to}) {
    const double h = f.height(*x);
    if (!(h >= low && h <= high)) return false;
    for (int e = 0; e < 3; ++e) {
      if (!(f.beyond(e, *x) <= -margin)) return false;
    }
  }
  return true;
}

}  // namespace palpate
