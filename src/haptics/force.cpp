#include "palpate/haptics/force.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "palpate/core/finite.hpp"

namespace palpate {
namespace {

constexpr float mm_per_m = 1000.0f;

}  // namespace

ForceResult spring_damper(const Contact& contact, glm::vec3 hip_velocity_mm_per_s, const Material& material,
                          float max_force_n) noexcept {
  ForceResult result;
  const float k = material.stiffness_n_per_mm, b = material.damping_ns_per_m;
  if (!is_finite(contact.hip_mm) || !is_finite(contact.point_mm) || !is_finite(contact.normal) ||
      !is_finite(hip_velocity_mm_per_s) || !std::isfinite(k) || !std::isfinite(b) ||
      !std::isfinite(max_force_n)) {
    result.invalid_input = true;
    return result;
  }
  if (!contact.in_contact()) return result;
  const glm::vec3 n = contact.normal;
  glm::vec3 force =
      k * (contact.point_mm - contact.hip_mm) - (b * glm::dot(hip_velocity_mm_per_s, n) / mm_per_m) * n;
  const float push = glm::dot(force, n);
  if (push < 0.0f) force -= push * n;
  const float magnitude = glm::length(force);
  if (!std::isfinite(magnitude)) {  // finite but astronomically far apart: overflowed
    result.invalid_input = true;
    return result;
  }
  const float limit = std::max(max_force_n, 0.0f);
  if (magnitude > limit) {
    force = magnitude > 0.0f ? force * (limit / magnitude) : glm::vec3(0.0f);
    result.clamped = true;
  }
  result.force_n = force;
  return result;
}

}  // namespace palpate
