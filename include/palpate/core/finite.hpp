#pragma once
// Whether every component of a vector is finite: the check at each boundary where a value from a
// device, a file or a caller enters palpate.
#include <cmath>
#include <glm/vec3.hpp>

namespace palpate {

template <class T, glm::qualifier Q>
bool is_finite(const glm::vec<3, T, Q>& v) noexcept {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace palpate
