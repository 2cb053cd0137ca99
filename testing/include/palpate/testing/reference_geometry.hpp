#pragma once
// Plain geometry written apart from palpate's core, by other methods, so that it can judge the core:
// the oracles of the tests and of `palpate bench haptics`. Slow and simple on purpose.
#include <glm/vec3.hpp>

namespace palpate::testing {

// The point of triangle (a, b, c) nearest to p: the projection onto the plane when it falls inside
// (barycentric coordinates), else the nearest point of the three edges. A degenerate triangle (a
// segment or a point) has no plane and gives the nearest point of its edges.
glm::dvec3 nearest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) noexcept;

// Whether the segment from -> to meets triangle (a, b, c) from either side, boundary included
// (Moller-Trumbore). A segment in the triangle's plane meets nothing.
bool segment_meets_triangle(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& a,
                            const glm::dvec3& b, const glm::dvec3& c) noexcept;

}  // namespace palpate::testing
