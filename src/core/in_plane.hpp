#pragma once
// A point laid into the plane of a line: the layout of a triangle's corner over an edge, for the
// distances along a surface.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace palpate {

// Where p lies in the plane with a at the origin and b on the +x axis, on the +y side.
inline glm::vec2 in_plane(glm::vec3 a, glm::vec3 b, glm::vec3 p) {
  const float length = glm::distance(a, b);
  const float x = glm::dot(p - a, b - a) / length;
  return {x, std::sqrt(std::max(glm::dot(p - a, p - a) - x * x, 0.0f))};
}

}  // namespace palpate
