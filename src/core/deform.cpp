#include "palpate/core/deform.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace palpate {

float dent_gaussian(float d, float depth_mm, float sigma_mm) noexcept {
  return depth_mm * std::exp(-(d * d) / (2.0f * sigma_mm * sigma_mm));
}

float dent_slope(float d, float depth_mm, float sigma_mm) noexcept {
  const float s2 = sigma_mm * sigma_mm;
  return -depth_mm * d / s2 * std::exp(-(d * d) / (2.0f * s2));
}

float dent_displacement(glm::vec3 v, std::span<const Dent> dents) noexcept {
  float sum = 0.0f;
  for (const Dent& dent : dents) {
    const glm::vec3 offset = v - dent.center_mm;
    const float d2 = glm::dot(offset, offset);
    const float cutoff = dent_cutoff_sigmas * dent.sigma_mm;
    if (d2 >= cutoff * cutoff) continue;
    sum += dent.depth_mm * std::exp(-d2 / (2.0f * dent.sigma_mm * dent.sigma_mm));
  }
  return sum;
}

glm::vec3 displaced_position(glm::vec3 v, glm::vec3 n, std::span<const Dent> dents) noexcept {
  return v - n * dent_displacement(v, dents);
}

glm::vec3 perturbed_normal(glm::vec3 n0, glm::vec3 v, std::span<const Dent> dents) noexcept {
  glm::vec3 n = n0;
  for (const Dent& dent : dents) {
    const glm::vec3 to_contact = dent.center_mm - v;  // VC
    const float d2 = glm::dot(to_contact, to_contact);
    const float cutoff = dent_cutoff_sigmas * dent.sigma_mm;
    if (d2 >= cutoff * cutoff) continue;
    const glm::vec3 w = glm::cross(n, to_contact);
    const float w_length2 = glm::dot(w, w);
    if (w_length2 <= 1e-12f * d2) continue;  // at the contact point or straight above it: no tilt
    const float tan_theta = -dent_slope(std::sqrt(d2), dent.depth_mm, dent.sigma_mm);
    const float cos_theta = 1.0f / std::sqrt(1.0f + tan_theta * tan_theta);
    const float sin_theta = tan_theta * cos_theta;
    const glm::vec3 axis = w / std::sqrt(w_length2);
    n = n * cos_theta + glm::cross(axis, n) * sin_theta;
  }
  return n;
}

Dent dent_in_space(const Dent& dent, const glm::mat4& to_space) noexcept {
  const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(to_space))));
  return Dent{glm::vec3(to_space * glm::vec4(dent.center_mm, 1.0f)), dent.depth_mm * scale,
              dent.sigma_mm * scale};
}

void deform_mesh(const Mesh& mesh, const glm::mat4& transform, std::span<const Dent> dents, Mesh& out) {
  const glm::mat3 rotation(transform);
  out.indices = mesh.indices;
  out.colors = mesh.colors;
  out.positions_mm.resize(mesh.positions_mm.size());
  out.normals.resize(mesh.positions_mm.size());
  const std::vector<glm::vec3>& directions = mesh.directions.empty() ? mesh.normals : mesh.directions;
  for (std::size_t i = 0; i < mesh.positions_mm.size(); ++i) {
    const glm::vec3 v = glm::vec3(transform * glm::vec4(mesh.positions_mm[i], 1.0f));
    out.positions_mm[i] = displaced_position(v, glm::normalize(rotation * directions[i]), dents);
  }
  compute_vertex_normals(out);
}

}  // namespace palpate
