#include "palpate/core/deform.hpp"

#include <algorithm>
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

namespace {

// d, and the vector toward the contact whose tangential part sets the tilt's direction (VC, or the
// sample's direction scaled to d).
struct DentReach {
  float distance;
  glm::vec3 toward;
};

DentReach dent_reach(const Dent& dent, bool first, glm::vec3 v, glm::vec4 sample) noexcept {
  const glm::vec3 to_contact = dent.center_mm - v;  // VC
  const float straight = glm::length(to_contact);
  if (!(first && dent.along_surface)) return {straight, to_contact};
  // What the shaders interpolate (deform.hpp), here at the vertex itself.
  const float along = sample.w;
  const glm::vec4 beyond_straight(glm::vec3(sample) * along - to_contact, along - straight);
  return {straight + beyond_straight.w, to_contact + glm::vec3(beyond_straight)};
}

}  // namespace

float dent_distance(const Dent& dent, glm::vec3 v, glm::vec4 surface_sample) noexcept {
  return dent_reach(dent, true, v, surface_sample).distance;
}

float dent_displacement(glm::vec3 v, std::span<const Dent> dents, glm::vec4 surface_sample) noexcept {
  float sum = 0.0f;
  for (std::size_t i = 0; i < dents.size(); ++i) {
    const Dent& dent = dents[i];
    const float d = dent_reach(dent, i == 0, v, surface_sample).distance;
    if (d >= dent_cutoff_sigmas * dent.sigma_mm) continue;
    sum += dent_gaussian(d, dent.depth_mm, dent.sigma_mm);
  }
  return sum;
}

namespace {

// Whether the dent pushes every vertex along -its normal (deform.hpp).
bool pushes_along_its_normal(const Dent& dent, bool first) noexcept {
  return first && dent.along_surface && glm::dot(dent.normal, dent.normal) > 0.0f;
}

}  // namespace

glm::vec3 displaced_position(glm::vec3 v, glm::vec3 n, std::span<const Dent> dents,
                             glm::vec4 surface_sample) noexcept {
  glm::vec3 moved = v;
  for (std::size_t i = 0; i < dents.size(); ++i) {
    const Dent& dent = dents[i];
    const float d = dent_reach(dent, i == 0, v, surface_sample).distance;
    if (d >= dent_cutoff_sigmas * dent.sigma_mm) continue;
    moved -= (pushes_along_its_normal(dent, i == 0) ? dent.normal : n) *
             dent_gaussian(d, dent.depth_mm, dent.sigma_mm);
  }
  return moved;
}

glm::vec3 perturbed_normal(glm::vec3 n0, glm::vec3 v, std::span<const Dent> dents,
                           glm::vec4 surface_sample) noexcept {
  glm::vec3 n = n0;
  for (std::size_t i = 0; i < dents.size(); ++i) {
    const Dent& dent = dents[i];
    const auto [d, toward] = dent_reach(dent, i == 0, v, surface_sample);
    if (d >= dent_cutoff_sigmas * dent.sigma_mm) continue;
    const glm::vec3 w = glm::cross(n, toward);
    const float w_length2 = glm::dot(w, w);
    if (w_length2 <= 1e-12f * glm::dot(toward, toward)) continue;  // at c or straight above it: no tilt
    const float tan_theta = -dent_slope(d, dent.depth_mm, dent.sigma_mm);
    const float cos_theta = 1.0f / std::sqrt(1.0f + tan_theta * tan_theta);
    const float sin_theta = tan_theta * cos_theta;
    const glm::vec3 axis = w / std::sqrt(w_length2);
    if (pushes_along_its_normal(dent, i == 0)) {  // N + (N x grad G) x n, with N x T = axis
      n = glm::normalize(n + glm::cross(axis, dent.normal) * tan_theta);
      continue;
    }
    n = n * cos_theta + glm::cross(axis, n) * sin_theta;
  }
  return n;
}

Dent dent_with_slope_limit(const Dent& dent, float max_slope) noexcept {
  Dent widened = dent;
  widened.sigma_mm = std::max(dent.sigma_mm, std::abs(dent.depth_mm) * 0.60653066f / max_slope);  // e^(-1/2)
  return widened;
}

Dent dent_in_space(const Dent& dent, const glm::mat4& to_space) noexcept {
  const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(to_space))));
  return Dent{glm::vec3(to_space * glm::vec4(dent.center_mm, 1.0f)), dent.depth_mm * scale,
              dent.sigma_mm * scale, dent.along_surface, glm::mat3(to_space) * dent.normal / scale};
}

glm::vec4 surface_sample_in_space(glm::vec4 sample, const glm::mat4& to_space) noexcept {
  const glm::mat3 linear(to_space);
  const float scale = std::cbrt(std::abs(glm::determinant(linear)));
  return glm::vec4(linear * glm::vec3(sample) / scale, sample.w * scale);
}

void deform_mesh(const Mesh& mesh, const glm::mat4& transform, std::span<const Dent> dents, Mesh& out,
                 std::span<const glm::vec4> surface_samples) {
  const glm::mat3 rotation(transform);
  out.indices = mesh.indices;
  out.colors = mesh.colors;
  out.positions_mm.resize(mesh.positions_mm.size());
  out.normals.resize(mesh.positions_mm.size());
  const std::vector<glm::vec3>& directions = mesh.directions.empty() ? mesh.normals : mesh.directions;
  for (std::size_t i = 0; i < mesh.positions_mm.size(); ++i) {
    const glm::vec3 v = glm::vec3(transform * glm::vec4(mesh.positions_mm[i], 1.0f));
    const glm::vec4 sample = surface_samples.empty()
                                 ? no_surface_sample
                                 : glm::vec4(rotation * glm::vec3(surface_samples[i]), surface_samples[i].w);
    out.positions_mm[i] = displaced_position(v, glm::normalize(rotation * directions[i]), dents, sample);
  }
  compute_vertex_normals(out);
}

}  // namespace palpate
