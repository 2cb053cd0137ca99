#include "palpate/core/surface_patch.hpp"

#include <algorithm>
#include <glm/geometric.hpp>
#include <limits>

#include "palpate/core/bvh.hpp"

namespace palpate {

SurfacePatch::SurfacePatch(const Mesh& mesh)
    : SurfacePatch(mesh, group_positions(mesh, default_weld_tolerance_mm(mesh))) {}

SurfacePatch::SurfacePatch(const Mesh& mesh, const PositionGroups& groups)
    : welded_(weld_by_position(mesh, groups)), field_(welded_) {
  first_copy_.assign(groups.count + 1, 0);
  for (const std::uint32_t g : groups.group) ++first_copy_[g + 1];
  for (std::size_t g = 0; g < groups.count; ++g) first_copy_[g + 1] += first_copy_[g];
  copies_.resize(groups.group.size());
  std::vector<std::uint32_t> filled(first_copy_.begin(), first_copy_.end() - 1);
  for (std::uint32_t v = 0; v < groups.group.size(); ++v) copies_[filled[groups.group[v]]++] = v;
  samples_.assign(mesh.vertex_count(), no_surface_sample);
  gradient_sum_.assign(groups.count, glm::vec3(0.0f));
  patch_.reserve(groups.count);
}

void SurfacePatch::write(std::uint32_t welded_vertex, glm::vec4 sample) noexcept {
  for (std::uint32_t i = first_copy_[welded_vertex]; i < first_copy_[welded_vertex + 1]; ++i) {
    const std::uint32_t v = copies_[i];
    samples_[v] = sample;
    const std::uint32_t end = std::max(changed_.first + changed_.count, v + 1);
    changed_.first = changed_.count == 0 ? v : std::min(changed_.first, v);
    changed_.count = end - changed_.first;
  }
}

void SurfacePatch::clear() noexcept {
  changed_ = {};
  for (const std::uint32_t w : patch_) write(w, no_surface_sample);
  patch_.clear();
}

std::uint32_t SurfacePatch::closest_triangle(glm::vec3 point_mm) const noexcept {
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t closest = 0;
  const glm::dvec3 p(point_mm);
  for (std::size_t t = 0; 3 * t < welded_.indices.size(); ++t) {
    const std::uint32_t* corners = &welded_.indices[3 * t];
    const glm::dvec3 q = closest_point_on_triangle(p, glm::dvec3(welded_.positions_mm[corners[0]]),
                                                   glm::dvec3(welded_.positions_mm[corners[1]]),
                                                   glm::dvec3(welded_.positions_mm[corners[2]]));
    const double distance2 = glm::dot(q - p, q - p);
    if (distance2 < best) best = distance2, closest = std::uint32_t(t);
  }
  return closest;
}

void SurfacePatch::compute(std::int64_t triangle, glm::vec3 point_mm, float radius_mm) noexcept {
  clear();
  const std::size_t triangles = welded_.indices.size() / 3;
  if (triangles == 0) return;
  const std::uint32_t contact = triangle >= 0 && std::size_t(triangle) < triangles
                                    ? std::uint32_t(triangle)
                                    : closest_triangle(point_mm);
  field_.compute(contact, point_mm, radius_mm);  // the triangle is in range: does not throw
  const std::uint32_t* corners = &welded_.indices[3 * std::size_t(contact)];
  const glm::vec3 face = glm::cross(welded_.positions_mm[corners[1]] - welded_.positions_mm[corners[0]],
                                    welded_.positions_mm[corners[2]] - welded_.positions_mm[corners[0]]);
  contact_normal_ = glm::length(face) > 0.0f ? glm::normalize(face) : glm::vec3(0.0f);

  // The direction of the distance's gradient at each vertex: the area-weighted mean of the gradients
  // of its linear interpolation over the triangles around it that lie wholly in the patch.
  const auto reached = field_.reached();
  const auto in_patch = [&](std::uint32_t v) { return field_.distance_mm(v) <= radius_mm; };
  for (const std::uint32_t v : reached) gradient_sum_[v] = glm::vec3(0.0f);
  for (const std::uint32_t v : reached) {
    for (const std::uint32_t t : field_.triangles_around(v)) {
      const std::uint32_t* c = &welded_.indices[3 * std::size_t(t)];
      if (!in_patch(c[0]) || !in_patch(c[1]) || !in_patch(c[2])) continue;
      const glm::vec3 p0 = welded_.positions_mm[c[0]];
      const glm::vec3 e1 = welded_.positions_mm[c[1]] - p0, e2 = welded_.positions_mm[c[2]] - p0;
      const glm::vec3 n = glm::cross(e1, e2);
      const float n2 = glm::dot(n, n);
      if (!(n2 > 0.0f)) continue;
      const float d0 = field_.distance_mm(c[0]);
      // grad = ((d1 - d0) e2 x n + (d2 - d0) n x e1) / |n|^2, weighted by the area (|n| / 2).
      const glm::vec3 gradient = ((field_.distance_mm(c[1]) - d0) * glm::cross(e2, n) +
                                  (field_.distance_mm(c[2]) - d0) * glm::cross(n, e1)) /
                                 n2;
      gradient_sum_[v] += gradient * std::sqrt(n2);
    }
  }
  for (const std::uint32_t v : reached) {
    const glm::vec3 position = welded_.positions_mm[v];
    const float length = glm::length(gradient_sum_[v]);
    const glm::vec3 straight = point_mm - position;
    const glm::vec3 toward = length > 0.0f                  ? -gradient_sum_[v] / length
                             : glm::length(straight) > 0.0f ? glm::normalize(straight)
                                                            : glm::vec3(0.0f);
    write(v, glm::vec4(toward, field_.distance_mm(v)));
    patch_.push_back(v);
  }
}

}  // namespace palpate
