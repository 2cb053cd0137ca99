#include "palpate/core/surface_patch.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace palpate {

SurfacePatch::SurfacePatch(const Mesh& mesh)
    : SurfacePatch(mesh, group_positions(mesh, default_weld_tolerance_mm(mesh))) {}

SurfacePatch::SurfacePatch(const Mesh& mesh, const PositionGroups& groups)
    : welded_(weld_by_position(mesh, groups)), field_(welded_) {
  Scene alone;
  alone.objects.push_back({"surface patch", welded_, glm::mat4(1.0f), Material{}, {}});
  walls_bvh_ = Bvh::build(alone);
  std::vector<std::uint32_t> stamps(welded_.triangle_count(), 0);
  clearance_mm_.resize(groups.count);
  for (std::uint32_t v = 0; v < groups.count; ++v) clearance_mm_[v] = clearance(v, stamps, v + 1);
  distance_mm_.assign(groups.count, std::numeric_limits<float>::infinity());
  push_mm_.assign(groups.count, 0.0f);
  pending_.assign(groups.count, 0);
  queued_.assign(groups.count, 0);
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
  for (const std::uint32_t w : patch_) {
    write(w, no_surface_sample);
    distance_mm_[w] = std::numeric_limits<float>::infinity();
  }
  patch_.clear();
  walls_ = 0;
}

// A ray from the vertex shorter than this meets no triangle but those of its two rings (its own sheet,
// where the dent's slope limit already keeps the order): the walls need no ray there. The distance to
// the nearest other triangle, found in the BVH with the rings' triangles stamped out.
float SurfacePatch::clearance(std::uint32_t welded_vertex, std::vector<std::uint32_t>& stamps,
                              std::uint32_t stamp) const {
  for (const std::uint32_t t : field_.triangles_around(welded_vertex)) {
    for (int k = 0; k < 3; ++k) {
      for (const std::uint32_t u :
           field_.triangles_around(welded_.indices[3 * std::size_t(t) + std::size_t(k)]))
        stamps[u] = stamp;
    }
  }
  const BvhHit nearest = walls_bvh_.closest_point_where(
      glm::dvec3(welded_.positions_mm[welded_vertex]), std::numeric_limits<double>::infinity(),
      [&](std::uint32_t primitive) { return stamps[walls_bvh_.triangle(primitive).id] != stamp; });
  return nearest.hit() ? nearest.distance_mm : std::numeric_limits<float>::infinity();
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
  march(triangle, point_mm, radius_mm);
  write_samples(point_mm, radius_mm);
}

void SurfacePatch::compute(std::int64_t triangle, glm::vec3 point_mm, PushedDent dent) noexcept {
  const float radius_mm = dent_cutoff_sigmas * dent.sigma_mm;
  march(triangle, point_mm, radius_mm);
  if (dent.depth_mm > 0.0f && dent.sigma_mm > 0.0f) give_way(dent);
  write_samples(point_mm, radius_mm);
}

void SurfacePatch::march(std::int64_t triangle, glm::vec3 point_mm, float radius_mm) noexcept {
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
  for (const std::uint32_t v : field_.reached()) {
    distance_mm_[v] = field_.distance_mm(v);
    patch_.push_back(v);
  }
}

// Written here, not found in a library: the walls are those of the one surface the march runs on. Each
// vertex the dent moves casts a ray along the push as far as the wall it could reach (G / 0.8); the
// corners of the triangle it hits move at least G - 0.8 t, drag their neighbours along and cast in
// turn. A ring of pending vertices, each in it at most once, so that nothing allocates.
void SurfacePatch::give_way(PushedDent dent) noexcept {
  const glm::vec3 push = -contact_normal_;
  if (glm::dot(push, push) == 0.0f) return;
  const float least_push = dent_gaussian(dent_cutoff_sigmas * dent.sigma_mm, dent.depth_mm, dent.sigma_mm);
  // The dent's vertices cast where they move by a tenth of p or more: the rays cost about 1 us each,
  // and below a tenth they found no wall the others missed on the real cortices (the same folds at
  // 2 sigma).
  const float least_ray_push = 0.1f * dent.depth_mm;
  const std::size_t ring = pending_.size();
  std::size_t head = 0, count = 0;
  constexpr std::uint8_t pending = 1, raised = 2;  // flags in queued_
  const auto enqueue = [&](std::uint32_t v) {
    if ((queued_[v] & pending) != 0) return;
    queued_[v] |= pending;
    pending_[(head + count++) % ring] = v;
  };
  for (const std::uint32_t v : patch_) {
    push_mm_[v] = dent_gaussian(distance_mm_[v], dent.depth_mm, dent.sigma_mm);
    if (push_mm_[v] > least_ray_push) enqueue(v);
  }
  // A vertex raised here drags its neighbours along: no more than surface_dent_max_slope between them
  // (the dent's own steepest slope), so that the part of a wall that gives way bends instead of
  // stepping (a step along the push turns the triangles of a wall parallel to it over) and covers the
  // wall between the rays.
  const auto raise = [&](std::uint32_t v, float needed) {
    if (std::isinf(distance_mm_[v])) {
      push_mm_[v] = 0.0f;
      distance_mm_[v] = std::numeric_limits<float>::max();  // in the patch from now on
      patch_.push_back(v);
    }
    if (push_mm_[v] >= needed || needed <= least_push) return;
    push_mm_[v] = needed;
    queued_[v] |= raised;
    enqueue(v);
  };
  constexpr float start_mm = 1.0e-3f;  // off the vertex's own triangles
  // Each raise is lower than the push that caused it, so the walk ends; the bound only guards it.
  for (std::size_t steps = 0; count > 0 && steps < 16 * ring; ++steps) {
    const std::uint32_t y = pending_[head];
    head = (head + 1) % ring, --count;
    queued_[y] &= std::uint8_t(~pending);
    const glm::vec3 from = welded_.positions_mm[y];
    if ((queued_[y] & raised) != 0) {
      for (const std::uint32_t t : field_.triangles_around(y)) {
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t n = welded_.indices[3 * std::size_t(t) + std::size_t(k)];
          if (n != y)
            raise(n, push_mm_[y] - surface_dent_max_slope * glm::distance(from, welded_.positions_mm[n]));
        }
      }
    }
    const float reach_mm = push_mm_[y] / wall_gap_slope;
    if (reach_mm <= start_mm || reach_mm < clearance_mm_[y]) continue;
    const BvhHit hit = walls_bvh_.first_hit(glm::dvec3(from + push * start_mm),
                                            glm::dvec3(from + push * reach_mm), Faces::both);
    if (!hit.hit()) continue;
    const std::uint32_t* corners = &welded_.indices[3 * std::size_t(hit.triangle)];
    if (corners[0] == y || corners[1] == y || corners[2] == y) continue;
    const float gap_mm = start_mm + hit.t * (reach_mm - start_mm);
    for (int k = 0; k < 3; ++k) raise(corners[k], push_mm_[y] - wall_gap_slope * gap_mm);
  }
  for (const std::uint32_t v : patch_) queued_[v] = 0;
  // The distance at which the dent's Gaussian gives each vertex its push.
  const float two_sigma2 = 2.0f * dent.sigma_mm * dent.sigma_mm;
  for (const std::uint32_t v : patch_) {
    if (push_mm_[v] <= least_push) continue;
    const float distance =
        std::sqrt(two_sigma2 * std::log(dent.depth_mm / std::min(push_mm_[v], dent.depth_mm)));
    if (distance < distance_mm_[v]) distance_mm_[v] = distance, ++walls_;
  }
}

void SurfacePatch::write_samples(glm::vec3 point_mm, float radius_mm) noexcept {
  // The direction of the distance's gradient at each vertex: the area-weighted mean of the gradients
  // of its linear interpolation over the triangles around it that lie wholly in the patch.
  const auto in_patch = [&](std::uint32_t v) { return distance_mm_[v] <= radius_mm; };
  for (const std::uint32_t v : patch_) gradient_sum_[v] = glm::vec3(0.0f);
  for (const std::uint32_t v : patch_) {
    if (!in_patch(v)) continue;
    for (const std::uint32_t t : field_.triangles_around(v)) {
      const std::uint32_t* c = &welded_.indices[3 * std::size_t(t)];
      if (v != std::min({c[0], c[1], c[2]})) continue;  // each triangle once, from its first corner
      if (!in_patch(c[0]) || !in_patch(c[1]) || !in_patch(c[2])) continue;
      const glm::vec3 p0 = welded_.positions_mm[c[0]];
      const glm::vec3 e1 = welded_.positions_mm[c[1]] - p0, e2 = welded_.positions_mm[c[2]] - p0;
      const glm::vec3 n = glm::cross(e1, e2);
      const float n2 = glm::dot(n, n);
      if (!(n2 > 0.0f)) continue;
      const float d0 = distance_mm_[c[0]];
      // grad = ((d1 - d0) e2 x n + (d2 - d0) n x e1) / |n|^2, weighted by the area (|n| / 2).
      const glm::vec3 gradient =
          ((distance_mm_[c[1]] - d0) * glm::cross(e2, n) + (distance_mm_[c[2]] - d0) * glm::cross(n, e1)) /
          n2;
      for (int k = 0; k < 3; ++k) gradient_sum_[c[k]] += gradient * std::sqrt(n2);
    }
  }
  std::size_t kept = 0;
  for (const std::uint32_t v : patch_) {
    if (!in_patch(v)) {  // a wall's corner that did not give way after all
      distance_mm_[v] = std::numeric_limits<float>::infinity();
      continue;
    }
    const glm::vec3 position = welded_.positions_mm[v];
    const float length = glm::length(gradient_sum_[v]);
    const glm::vec3 straight = point_mm - position;
    const glm::vec3 toward = length > 0.0f                  ? -gradient_sum_[v] / length
                             : glm::length(straight) > 0.0f ? glm::normalize(straight)
                                                            : glm::vec3(0.0f);
    write(v, glm::vec4(toward, distance_mm_[v]));
    patch_[kept++] = v;
  }
  patch_.resize(kept);
}

}  // namespace palpate
