#include "palpate/testing/reference_geometry.hpp"

#include <algorithm>
#include <glm/geometric.hpp>
#include <iterator>

namespace palpate::testing {
namespace {

glm::dvec3 nearest_on_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) noexcept {
  const glm::dvec3 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  if (length2 == 0.0) return a;
  return a + ab * std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0);
}

}  // namespace

glm::dvec3 nearest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) noexcept {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double area2 = glm::dot(n, n);
  if (area2 > 0.0) {
    const glm::dvec3 q = p - n * (glm::dot(p - a, n) / area2);
    // Barycentric coordinates of q from the sub-triangles' signed areas.
    const double u = glm::dot(glm::cross(c - b, q - b), n) / area2;
    const double v = glm::dot(glm::cross(a - c, q - c), n) / area2;
    const double w = 1.0 - u - v;
    if (u >= 0.0 && v >= 0.0 && w >= 0.0) return q;
  }
  const glm::dvec3 candidates[] = {nearest_on_segment(p, a, b), nearest_on_segment(p, b, c),
                                   nearest_on_segment(p, c, a)};
  return *std::min_element(std::begin(candidates), std::end(candidates),
                           [&](const glm::dvec3& x, const glm::dvec3& y) {
                             return glm::dot(x - p, x - p) < glm::dot(y - p, y - p);
                           });
}

bool segment_meets_triangle(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& a,
                            const glm::dvec3& b, const glm::dvec3& c) noexcept {
  const glm::dvec3 d = to - from;
  const glm::dvec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  if (det == 0.0) return false;
  const glm::dvec3 tv = from - a;
  const double u = glm::dot(tv, pv) / det;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 qv = glm::cross(tv, e1);
  const double v = glm::dot(d, qv) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double s = glm::dot(e2, qv) / det;
  return s >= 0.0 && s <= 1.0;
}

}  // namespace palpate::testing
