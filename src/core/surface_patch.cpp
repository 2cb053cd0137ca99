#include "palpate/core/surface_patch.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <numeric>

namespace palpate {
namespace {

// How far apart in number a triangle's corners lie, on average, with the mesh's vertex v numbered number[v].
double mean_corner_spread(const Mesh& mesh, const std::vector<std::uint32_t>& number) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const std::uint32_t a = number[mesh.indices[i]], b = number[mesh.indices[i + 1]],
                        c = number[mesh.indices[i + 2]];
    sum += double(std::max({a, b, c}) - std::min({a, b, c}));
  }
  return sum / double(std::max<std::size_t>(mesh.indices.size() / 3, 1));
}

// The march and the walls read each vertex's and each triangle's neighbours: numbered near one another,
// they share cache lines. Meshes come in any order: the Colin27 brain's, after the decimation, is
// scattered over the surface, and renumbered its march takes 20-30% less time; the SPM12 cortex's
// (a subdivided icosahedron) is already more local than the curve's, and renumbered its march took
// 15% more (docs/design.md). So the groups are renumbered along meshoptimizer's space-filling curve, and
// the triangles put in the order of their lowest corner, only where that brings the corners nearer;
// `welded_triangle` gets each triangle's number in the welded mesh.
Mesh weld_in_spatial_order(const Mesh& mesh, PositionGroups& groups,
                           std::vector<std::uint32_t>& welded_triangle) {
  std::vector<glm::vec3> positions(groups.count);
  for (std::size_t v = 0; v < groups.group.size(); ++v) positions[groups.group[v]] = mesh.positions_mm[v];
  std::vector<unsigned int> renumbered(groups.count);
  meshopt_spatialSortRemap(renumbered.data(), &positions.data()->x, positions.size(), sizeof(glm::vec3));
  std::vector<std::uint32_t> along_curve(groups.group.size());
  for (std::size_t v = 0; v < along_curve.size(); ++v) along_curve[v] = renumbered[groups.group[v]];
  const bool nearer = mean_corner_spread(mesh, along_curve) < mean_corner_spread(mesh, groups.group);
  if (nearer) groups.group = std::move(along_curve);

  Mesh welded = weld_by_position(mesh, groups);
  const std::size_t triangles = welded.indices.size() / 3;
  std::vector<std::uint32_t> order(triangles), lowest(triangles);
  std::iota(order.begin(), order.end(), 0u);
  welded_triangle = order;
  if (!nearer) return welded;
  for (std::size_t t = 0; t < triangles; ++t)
    lowest[t] = std::min({welded.indices[3 * t], welded.indices[3 * t + 1], welded.indices[3 * t + 2]});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return lowest[a] < lowest[b]; });
  const std::vector<std::uint32_t> indices = std::move(welded.indices);
  welded.indices.resize(indices.size());
  for (std::size_t t = 0; t < triangles; ++t) {
    welded_triangle[order[t]] = std::uint32_t(t);
    std::copy_n(&indices[3 * std::size_t(order[t])], 3, &welded.indices[3 * t]);
  }
  return welded;
}

}  // namespace

SurfacePatch::SurfacePatch(const Mesh& mesh)
    : SurfacePatch(mesh, group_positions(mesh, default_weld_tolerance_mm(mesh))) {}

SurfacePatch::SurfacePatch(const Mesh& mesh, PositionGroups groups)
    : welded_(weld_in_spatial_order(mesh, groups, welded_triangle_)), field_(welded_) {
  field_.reserve(window_budget);
  Scene alone;
  alone.objects.push_back({"surface patch", welded_, glm::mat4(1.0f), Material{}, {}});
  walls_bvh_ = Bvh::build(alone);
  std::vector<std::uint32_t> stamps(welded_.triangle_count(), 0);
  std::vector<float> vertex_clearance_mm(groups.count);
  for (std::uint32_t v = 0; v < groups.count; ++v) vertex_clearance_mm[v] = clearance(v, stamps, v + 1);
  // A triangle's: a point of it lies within its longest edge over sqrt(3) of a corner (the equilateral's
  // centre is the worst case). Measured at a 1 mm press (Colin27, sigma 4 mm): with it a quarter of the
  // dent's triangles look behind them, with the whole longest edge 83%.
  // Each vertex's longest edge too (wall_push_cap).
  clearance_mm_.resize(welded_.triangle_count());
  longest_edge_mm_.assign(groups.count, 0.0f);
  for (std::size_t t = 0; t < clearance_mm_.size(); ++t) {
    const std::uint32_t* c = &welded_.indices[3 * t];
    float edge[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = c[k], b = c[(k + 1) % 3];
      edge[k] = glm::distance(welded_.positions_mm[a], welded_.positions_mm[b]);
      longest_edge_mm_[a] = std::max(longest_edge_mm_[a], edge[k]);
      longest_edge_mm_[b] = std::max(longest_edge_mm_[b], edge[k]);
    }
    clearance_mm_[t] =
        std::min({vertex_clearance_mm[c[0]], vertex_clearance_mm[c[1]], vertex_clearance_mm[c[2]]}) -
        std::max({edge[0], edge[1], edge[2]}) / std::sqrt(3.0f);
  }
  // And looking only behind: a triangle pushed against its own normal's side sweeps only the half-space
  // behind its plane, where the nearest other triangle is often further (a crown's facing gyrus lies
  // beside it, not behind).
  back_clearance_mm_.resize(welded_.triangle_count());
  for (std::uint32_t t = 0; t < back_clearance_mm_.size(); ++t)
    back_clearance_mm_[t] = clearance_behind(t, stamps, groups.count + 1 + t);
  assign_clusters();
  distance_mm_.assign(groups.count, std::numeric_limits<float>::infinity());
  push_mm_.assign(groups.count, 0.0f);
  pending_.assign(groups.count, 0);
  queued_.assign(groups.count, 0);
  unsettled_.assign(welded_.triangle_count(), 0);
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

// Clusters: the largest subtrees of the walls' BVH with at most cluster_triangles triangles.
void SurfacePatch::assign_clusters() {
  constexpr std::uint32_t cluster_triangles = 32;
  const std::vector<Bvh::Node>& nodes = walls_bvh_.nodes();
  cluster_of_.assign(welded_.triangle_count(), 0);
  clusters_.clear();
  if (nodes.empty()) return;
  std::vector<std::uint32_t> size(nodes.size(), 0);
  for (std::size_t n = nodes.size(); n-- > 0;)
    size[n] = nodes[n].count > 0 ? nodes[n].count : size[nodes[n].first] + size[nodes[n].first + 1];
  std::vector<std::uint32_t> stack{0}, under;
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    if (size[n] > cluster_triangles && nodes[n].count == 0) {
      stack.push_back(nodes[n].first);
      stack.push_back(nodes[n].first + 1);
      continue;
    }
    const std::uint32_t cluster = std::uint32_t(clusters_.size());
    clusters_.push_back({nodes[n].min, nodes[n].max, 0.0f});
    under.assign(1, n);
    while (!under.empty()) {
      const Bvh::Node& node = nodes[under.back()];
      under.pop_back();
      if (node.count == 0) {
        under.push_back(node.first);
        under.push_back(node.first + 1);
        continue;
      }
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const std::uint32_t t = walls_bvh_.triangle(i).id;
        cluster_of_[t] = cluster;
        for (int k = 0; k < 3; ++k)
          clusters_[cluster].longest_edge_mm =
              std::max(clusters_[cluster].longest_edge_mm, longest_edge_mm_[welded_.indices[3 * t + k]]);
      }
    }
  }
  cluster_press_.assign(clusters_.size(), 0);
  cluster_first_.assign(clusters_.size(), 0);
  cluster_count_.assign(clusters_.size(), 0);
  // As many as the mesh has triangles: 8 mm presses at sigma 8 mm on Colin27 gather 11,000 on average,
  // 26,000 at most (100 presses).
  wall_candidates_.reserve(welded_.triangle_count());
  wall_meets_.resize(welded_.triangle_count());
  wall_met_.resize(welded_.triangle_count());
}

void SurfacePatch::WallCandidates::reserve(std::size_t count) {
  triangle.reserve(count);
  corners.reserve(count);
  for (std::vector<float>* bounds :
       {&depth_low, &depth_high, &across_low, &across_high, &across2_low, &across2_high})
    bounds->reserve(count);
}

void SurfacePatch::WallCandidates::clear() noexcept {
  triangle.clear();
  corners.clear();
  for (std::vector<float>* bounds :
       {&depth_low, &depth_high, &across_low, &across_high, &across2_low, &across2_high})
    bounds->clear();
}

void SurfacePatch::WallCandidates::push_back(std::uint32_t wall, const Corners& c) {
  triangle.push_back(wall);
  corners.push_back({c.vertex[0], c.vertex[1], c.vertex[2]});
  depth_low.push_back(std::min({c.depth[0], c.depth[1], c.depth[2]}));
  depth_high.push_back(std::max({c.depth[0], c.depth[1], c.depth[2]}));
  across_low.push_back(std::min({c.outline[0].x, c.outline[1].x, c.outline[2].x}));
  across_high.push_back(std::max({c.outline[0].x, c.outline[1].x, c.outline[2].x}));
  across2_low.push_back(std::min({c.outline[0].y, c.outline[1].y, c.outline[2].y}));
  across2_high.push_back(std::max({c.outline[0].y, c.outline[1].y, c.outline[2].y}));
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
  last_press_.reset();
  for (const std::uint32_t w : patch_) {
    write(w, no_surface_sample);
    distance_mm_[w] = std::numeric_limits<float>::infinity();
    push_mm_[w] = 0.0f;  // a corner outside the next patch pushes nothing
  }
  patch_.clear();
  walls_ = 0;
  moved_reach_mm_ = 0.0f;
}

// A look from the vertex shorter than this meets no triangle but those of its two rings (its own sheet,
// where the dent's slope limit and the upright rule keep the order): the walls need no look there. The
// distance to the nearest other triangle, found in the BVH with the rings' triangles stamped out.
// Marks with `stamp` the triangles of a welded vertex's two rings: its own sheet, left to the upright rule.
void SurfacePatch::stamp_two_rings(std::uint32_t welded_vertex, std::vector<std::uint32_t>& stamps,
                                   std::uint32_t stamp) const {
  for (const std::uint32_t t : field_.triangles_around(welded_vertex)) {
    for (int k = 0; k < 3; ++k) {
      for (const std::uint32_t u :
           field_.triangles_around(welded_.indices[3 * std::size_t(t) + std::size_t(k)]))
        stamps[u] = stamp;
    }
  }
}

float SurfacePatch::clearance(std::uint32_t welded_vertex, std::vector<std::uint32_t>& stamps,
                              std::uint32_t stamp) const {
  stamp_two_rings(welded_vertex, stamps, stamp);
  const BvhHit nearest = walls_bvh_.closest_point_where(
      glm::dvec3(welded_.positions_mm[welded_vertex]), std::numeric_limits<double>::infinity(),
      [&](std::uint32_t primitive) { return stamps[walls_bvh_.triangle(primitive).id] != stamp; });
  return nearest.hit() ? nearest.distance_mm : std::numeric_limits<float>::infinity();
}

// The distance from a triangle's centre to the nearest triangle beyond its corners' two rings with a point
// behind its plane (or within 0.01 mm before it), less the centre's distance to its furthest corner.
float SurfacePatch::clearance_behind(std::uint32_t triangle, std::vector<std::uint32_t>& stamps,
                                     std::uint32_t stamp) const {
  const std::uint32_t* corner = &welded_.indices[3 * std::size_t(triangle)];
  const glm::vec3 p0 = welded_.positions_mm[corner[0]], p1 = welded_.positions_mm[corner[1]],
                  p2 = welded_.positions_mm[corner[2]];
  const glm::vec3 face = glm::cross(p1 - p0, p2 - p0);
  if (!(glm::length(face) > 0.0f)) return clearance_mm_[triangle];
  const glm::vec3 normal = glm::normalize(face), centre = (p0 + p1 + p2) / 3.0f;
  for (int k = 0; k < 3; ++k) stamp_two_rings(corner[k], stamps, stamp);
  constexpr float plane_tolerance_mm = 0.01f;
  const BvhHit nearest = walls_bvh_.closest_point_where(
      glm::dvec3(centre), std::numeric_limits<double>::infinity(), [&](std::uint32_t primitive) {
        const Bvh::Triangle& other = walls_bvh_.triangle(primitive);
        if (stamps[other.id] == stamp) return false;
        for (const glm::vec3& p : other.vertices)
          if (glm::dot(p - centre, normal) < plane_tolerance_mm) return true;
        return false;
      });
  if (!nearest.hit()) return std::numeric_limits<float>::infinity();
  return float(nearest.distance_mm) -
         std::max({glm::distance(centre, p0), glm::distance(centre, p1), glm::distance(centre, p2)});
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
  // A mouse at rest or a scripted hold asks for the same press frame after frame: the whole update is
  // saved (on the Colin27 brain at sigma 8 mm, 3-6 ms of a 19 ms frame on llvmpipe).
  const Press press{triangle, point_mm, dent};
  if (last_press_ == press) {
    changed_ = {};
    return;
  }
  const float radius_mm = dent_cutoff_sigmas * dent.sigma_mm;
  march(triangle, point_mm, radius_mm);
  if (dent.depth_mm > 0.0f && dent.sigma_mm > 0.0f) give_way(point_mm, dent);
  write_samples(point_mm, radius_mm);
  last_press_ = press;
}

void SurfacePatch::march(std::int64_t triangle, glm::vec3 point_mm, float radius_mm) noexcept {
  clear();
  const std::size_t triangles = welded_.indices.size() / 3;
  if (triangles == 0) return;
  const std::uint32_t contact = triangle >= 0 && std::size_t(triangle) < triangles
                                    ? welded_triangle_[std::size_t(triangle)]
                                    : closest_triangle(point_mm);
  // Exact out to 2 sigma of the dent's 4, where the weight is steep (its slope is largest at 1 sigma),
  // or as far as window_budget windows reach. Fast marching beyond, its second look out to 3 sigma: the
  // weight there is under 1.1% of p, so the few percent the march's edge arrivals leave change it by at most
  // 0.0027 of p (over 200 presses of 8 mm at sigma 8 mm on Colin27), for about a tenth of the march's time.
  const GeodesicField::Reach reach{0.5f * radius_mm, window_budget, 0.75f * radius_mm};
  field_.compute(contact, point_mm, radius_mm, reach);  // the triangle is in range
  const std::uint32_t* corners = &welded_.indices[3 * std::size_t(contact)];
  const glm::vec3 face = glm::cross(welded_.positions_mm[corners[1]] - welded_.positions_mm[corners[0]],
                                    welded_.positions_mm[corners[2]] - welded_.positions_mm[corners[0]]);
  contact_normal_ = glm::length(face) > 0.0f ? glm::normalize(face) : glm::vec3(0.0f);
  for (const std::uint32_t v : field_.reached()) {
    distance_mm_[v] = std::max(field_.distance_mm(v), glm::distance(welded_.positions_mm[v], point_mm));
    patch_.push_back(v);
  }
}

namespace {

float cross2(glm::vec2 a, glm::vec2 b) {
  return a.x * b.y - a.y * b.x;
}

// Barycentric coordinates of x in the plane triangle (a, b, c), or none (x.z < 0) when it is flat.
glm::vec3 barycentric(glm::vec2 x, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
  const float area = cross2(b - a, c - a);
  if (!(std::abs(area) > 1e-12f)) return glm::vec3(-1.0f);
  const float lb = cross2(x - a, c - a) / area, lc = cross2(b - a, x - a) / area;
  return {1.0f - lb - lc, lb, lc};
}

}  // namespace

// The least push every corner of `wall` needs so that the triangle `front`, pushed, keeps a fifth of its
// gap to it wherever it lies behind `front` along the push (and the push that keeps 0.15 of it). Pushed one
// way, the two can only meet on a line along the push, and over the overlap of their outlines seen along it
// the gap between them is linear: it is enough to keep it at the overlap's corners (a corner of one inside
// the other, or two edges crossing). -inf where the outlines do not overlap or `wall` is not behind.
SurfacePatch::WallPush SurfacePatch::least_wall_push(const Corners& front,
                                                     const Corners& wall) const noexcept {
  constexpr WallPush none{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  // Most triangles near the front are not behind it, or their outlines miss its own: cheap to see.
  const auto lowest = [](const float* values) { return std::min({values[0], values[1], values[2]}); };
  const auto highest = [](const float* values) { return std::max({values[0], values[1], values[2]}); };
  if (highest(wall.depth) <= lowest(front.depth)) return none;
  const glm::vec2 front_low = glm::min(glm::min(front.outline[0], front.outline[1]), front.outline[2]),
                  front_high = glm::max(glm::max(front.outline[0], front.outline[1]), front.outline[2]),
                  wall_low = glm::min(glm::min(wall.outline[0], wall.outline[1]), wall.outline[2]),
                  wall_high = glm::max(glm::max(wall.outline[0], wall.outline[1]), wall.outline[2]);
  if (glm::any(glm::greaterThan(front_low, wall_high)) || glm::any(glm::greaterThan(wall_low, front_high)))
    return none;
  struct Meeting {
    float front_depth, front_push, wall_depth;
  };
  Meeting meetings[15];
  int count = 0;
  const auto dot3 = [](glm::vec3 weights, const float* values) {
    return weights.x * values[0] + weights.y * values[1] + weights.z * values[2];
  };
  for (int k = 0; k < 3; ++k) {
    const glm::vec3 in_wall =
        barycentric(front.outline[k], wall.outline[0], wall.outline[1], wall.outline[2]);
    if (glm::all(glm::greaterThanEqual(in_wall, glm::vec3(0.0f))))
      meetings[count++] = {front.depth[k], front.push[k], dot3(in_wall, wall.depth)};
    const glm::vec3 in_front =
        barycentric(wall.outline[k], front.outline[0], front.outline[1], front.outline[2]);
    if (glm::all(glm::greaterThanEqual(in_front, glm::vec3(0.0f))))
      meetings[count++] = {dot3(in_front, front.depth), dot3(in_front, front.push), wall.depth[k]};
  }
  for (int i = 0; i < 3; ++i) {
    const int i2 = (i + 1) % 3;
    const glm::vec2 p = front.outline[i], along_p = front.outline[i2] - p;
    for (int j = 0; j < 3; ++j) {
      const int j2 = (j + 1) % 3;
      const glm::vec2 q = wall.outline[j], along_q = wall.outline[j2] - q;
      const float den = cross2(along_p, along_q);
      if (den == 0.0f) continue;
      const float a = cross2(q - p, along_q) / den, b = cross2(q - p, along_p) / den;
      if (a < 0.0f || a > 1.0f || b < 0.0f || b > 1.0f) continue;
      meetings[count++] = {front.depth[i] + a * (front.depth[i2] - front.depth[i]),
                           front.push[i] + a * (front.push[i2] - front.push[i]),
                           wall.depth[j] + b * (wall.depth[j2] - wall.depth[j])};
    }
  }
  WallPush push = none;
  for (int m = 0; m < count; ++m) {
    const float gap = meetings[m].wall_depth - meetings[m].front_depth;
    if (gap <= 0.0f) return none;  // not behind
    push.least = std::max(push.least, meetings[m].front_push - wall_gap_slope * gap);
    push.enough = std::max(push.enough, meetings[m].front_push - wall_gap_slope_enough * gap);
  }
  return push;
}

// The most a vertex `distance_mm` from the contact, with edges up to `longest_edge_mm`, moves: the
// straight line's Gaussian two of its longest edges nearer the contact. A coarse wall's triangle lies
// behind the dent's deepest part where its corners are far from the contact (on the SPM12 cortex, capped
// at each corner's own, 30 of 20 presses of 2 sigma left triangles crossing).
float SurfacePatch::wall_push_cap(float distance_mm, float longest_edge_mm, PushedDent dent) noexcept {
  return dent_gaussian(std::max(distance_mm - wall_reach_edges * longest_edge_mm, 0.0f), dent.depth_mm,
                       dent.sigma_mm);
}

float SurfacePatch::wall_reach_mm(std::uint32_t triangle) const noexcept {
  if (triangle >= welded_triangle_.size()) return 0.0f;
  const std::uint32_t* corners = &welded_.indices[3 * std::size_t(welded_triangle_[triangle])];
  return wall_reach_edges *
         std::max({longest_edge_mm_[corners[0]], longest_edge_mm_[corners[1]], longest_edge_mm_[corners[2]]});
}

// Every triangle that a triangle of `cluster` could reach along the push this press: its pushes are at most
// wall_push_cap at the cluster's bounds.
void SurfacePatch::gather_walls(std::uint32_t cluster, glm::vec3 point_mm, PushedDent dent,
                                const Frame& frame) noexcept {
  const Cluster& c = clusters_[cluster];
  const float reach_mm =
      wall_push_cap(glm::distance(glm::clamp(point_mm, c.low, c.high), point_mm), c.longest_edge_mm, dent) /
      wall_gap_slope;
  const glm::vec3 swept = frame.push * reach_mm;
  cluster_press_[cluster] = press_number_;
  cluster_first_[cluster] = wall_candidates_.size();
  walls_bvh_.for_each_in_box(glm::min(c.low, c.low + swept), glm::max(c.high, c.high + swept),
                             [&](std::uint32_t primitive) {
                               const std::uint32_t u = walls_bvh_.triangle(primitive).id;
                               wall_candidates_.push_back(u, corners_of(u, frame));
                             });
  cluster_count_[cluster] = wall_candidates_.size() - cluster_first_[cluster];
  if (wall_meets_.size() < cluster_count_[cluster]) {  // not on any mesh measured: see assign_clusters
    wall_meets_.resize(cluster_count_[cluster]);
    wall_met_.resize(cluster_count_[cluster]);
  }
}

// The candidates of `cluster` (numbered from its first) whose bounds meet those of the prism `front` sweeps
// as far as `reach_mm` along the push: its outline's box seen along the push, and its depths along it.
std::span<const std::uint32_t> SurfacePatch::walls_met(const Corners& front, float reach_mm,
                                                       std::uint32_t cluster) noexcept {
  const glm::vec2 low = glm::min(glm::min(front.outline[0], front.outline[1]), front.outline[2]),
                  high = glm::max(glm::max(front.outline[0], front.outline[1]), front.outline[2]);
  const float near = std::min({front.depth[0], front.depth[1], front.depth[2]}),
              far = std::max({front.depth[0], front.depth[1], front.depth[2]}) + reach_mm;
  const std::uint32_t first = cluster_first_[cluster], candidates = cluster_count_[cluster];
  const WallCandidates& c = wall_candidates_;
  const float *depth_low = &c.depth_low[first], *depth_high = &c.depth_high[first],
              *across_low = &c.across_low[first], *across_high = &c.across_high[first],
              *across2_low = &c.across2_low[first], *across2_high = &c.across2_high[first];
  std::uint8_t* meets = wall_meets_.data();
  for (std::uint32_t i = 0; i < candidates; ++i)  // no branch: vectorised
    meets[i] = (depth_high[i] >= near) & (depth_low[i] <= far) & (across_low[i] <= high.x) &
               (across_high[i] >= low.x) & (across2_low[i] <= high.y) & (across2_high[i] >= low.y);
  std::uint32_t met = 0;  // one branch a candidate would be mispredicted half the time
  for (std::uint32_t i = 0; i < candidates; ++i) {
    wall_met_[met] = i;
    met += meets[i];
  }
  return {wall_met_.data(), met};
}

// How much of a triangle's normal the pushed triangle keeps, 1 + push . grad(push), and each corner's
// share of the gradient (`along`, per mm of push); 0 shares for a triangle without area.
void SurfacePatch::upright_share(const Corners& c, const Frame& frame, float along[3],
                                 float& upright) const noexcept {
  const glm::vec3 p0 = welded_.positions_mm[c.vertex[0]], p1 = welded_.positions_mm[c.vertex[1]],
                  p2 = welded_.positions_mm[c.vertex[2]];
  const glm::vec3 normal = glm::cross(p1 - p0, p2 - p0);
  const float normal2 = glm::dot(normal, normal);
  const glm::vec3 edges[3] = {p2 - p1, p0 - p2, p1 - p0};
  upright = 1.0f;
  for (int k = 0; k < 3; ++k) {
    along[k] = normal2 > 0.0f ? glm::dot(frame.push, glm::cross(normal, edges[k])) / normal2 : 0.0f;
    upright += along[k] * c.push[k];
  }
}

SurfacePatch::Corners SurfacePatch::corners_of(std::uint32_t triangle, const Frame& frame) const noexcept {
  Corners corners;
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = welded_.indices[3 * std::size_t(triangle) + std::size_t(k)];
    const glm::vec3 p = welded_.positions_mm[v];
    corners.vertex[k] = v;
    corners.outline[k] = {glm::dot(p, frame.across), glm::dot(p, frame.across2)};
    corners.depth[k] = glm::dot(p, frame.push);
    corners.push[k] = push_mm_[v];
  }
  return corners;
}

// Written here, not found in a library: the walls are those of the one surface the march runs on.
// Each triangle the dent moves looks along the push as far as the wall it could reach (its largest
// push / 0.8) for triangles behind it; their corners move enough to keep a fifth of the gap
// (least_wall_push) and look in turn. A ring of pending vertices, each in
// it at most once, so that nothing allocates.
void SurfacePatch::give_way(glm::vec3 point_mm, PushedDent dent) noexcept {
  Frame frame;
  frame.push = -contact_normal_;
  if (glm::dot(frame.push, frame.push) == 0.0f) return;
  frame.across = glm::normalize(std::abs(frame.push.x) < 0.6f ? glm::cross(frame.push, glm::vec3(1, 0, 0))
                                                              : glm::cross(frame.push, glm::vec3(0, 1, 0)));
  frame.across2 = glm::cross(frame.push, frame.across);
  const float least_push = dent_gaussian(dent_cutoff_sigmas * dent.sigma_mm, dent.depth_mm, dent.sigma_mm);
  const std::size_t ring = pending_.size();
  std::size_t head = 0, count = 0;
  if (++press_number_ == 0) {  // after 2^32 presses: no list is of this one
    std::fill(cluster_press_.begin(), cluster_press_.end(), 0u);
    press_number_ = 1;
  }
  wall_candidates_.clear();
  constexpr std::uint8_t pending = 1, lowered = 2;         // flags in queued_
  constexpr std::uint8_t unsettled = 1, turning_over = 2;  // flags in unsettled_
  const auto enqueue = [&](std::uint32_t v) {
    for (const std::uint32_t t : field_.triangles_around(v)) unsettled_[t] = unsettled;
    if ((queued_[v] & pending) != 0) return;
    queued_[v] |= pending;
    pending_[(head + count++) % ring] = v;
  };
  for (const std::uint32_t v : patch_) {
    push_mm_[v] = dent_gaussian(distance_mm_[v], dent.depth_mm, dent.sigma_mm);
    enqueue(v);
  }
  const auto raise = [&](std::uint32_t v, float needed, float enough) {
    if (std::isinf(distance_mm_[v])) {
      if (needed <= least_push) return;
      push_mm_[v] = 0.0f;
      distance_mm_[v] = std::numeric_limits<float>::max();  // in the patch from now on
      patch_.push_back(v);
    }
    needed = std::min(
        needed, wall_push_cap(glm::distance(welded_.positions_mm[v], point_mm), longest_edge_mm_[v], dent));
    if (push_mm_[v] >= std::min(needed, enough) || needed <= least_push) return;
    push_mm_[v] = needed;
    enqueue(v);
  };
  // A triangle whose push grows against the push's direction turns over where that growth passes 1 per
  // mm along the push (the deformed normal's share of the old one is 1 + push . grad(push)); its
  // corners further along the push move on until it keeps a fifth.
  // Says whether it found the triangle turning over.
  const auto keep_upright = [&](const Corners& c) {
    float along[3], upright = 1.0f, rising = 0.0f;
    upright_share(c, frame, along, upright);
    for (int k = 0; k < 3; ++k) rising += std::max(along[k], 0.0f);
    constexpr float kept = 1.0f - wall_gap_slope;
    if (upright >= kept) return false;
    if (!(rising > 0.0f)) return true;
    const float more = (kept - upright) / rising;
    for (int k = 0; k < 3; ++k)
      if (along[k] > 0.0f) raise(c.vertex[k], c.push[k] + more, c.push[k] + more);
    return true;
  };
  // Pushes only grow, and never past their cap, so the walk settles; the bound only guards it.
  for (std::size_t steps = 0; count > 0 && steps < 16 * ring; ++steps) {
    const std::uint32_t y = pending_[head];
    head = (head + 1) % ring, --count;
    queued_[y] &= std::uint8_t(~pending);
    for (const std::uint32_t t : field_.triangles_around(y)) {
      if ((unsettled_[t] & unsettled) == 0) continue;
      unsettled_[t] = 0;
      const Corners front = corners_of(t, frame);
      // A triangle raised to stay upright is looked at again; one the cap on its corners held back
      // stays marked for the sweeps below.
      if (keep_upright(front)) unsettled_[t] |= turning_over;
      const float reach_mm = std::max({front.push[0], front.push[1], front.push[2]}) / wall_gap_slope;
      // Pushed against its normal's side (its outline seen along the push turns clockwise), it sweeps
      // only the half-space behind it.
      const bool backward =
          cross2(front.outline[1] - front.outline[0], front.outline[2] - front.outline[0]) <= 0.0f;
      if (!(reach_mm > 0.0f) || reach_mm < (backward ? back_clearance_mm_[t] : clearance_mm_[t])) continue;
      const std::uint32_t cluster = cluster_of_[t];
      if (cluster_press_[cluster] != press_number_) gather_walls(cluster, point_mm, dent, frame);
      const std::uint32_t first = cluster_first_[cluster];
      const float front_deepest = std::max({front.depth[0], front.depth[1], front.depth[2]}),
                  front_push = std::max({front.push[0], front.push[1], front.push[2]});
      for (const std::uint32_t i : walls_met(front, reach_mm, cluster)) {
        const std::uint32_t u = wall_candidates_.triangle[first + i];
        const std::uint32_t* w = wall_candidates_.corners[first + i].data();
        const std::uint32_t f0 = front.vertex[0], f1 = front.vertex[1], f2 = front.vertex[2];
        const bool shares_a_corner = (w[0] == f0) | (w[0] == f1) | (w[0] == f2) | (w[1] == f0) |
                                     (w[1] == f1) | (w[1] == f2) | (w[2] == f0) | (w[2] == f1) | (w[2] == f2);
        // The most the wall could need (the front's largest push less the least gap) against what its
        // corners already have: most walls are the dent's own, pushed as far.
        const float most =
            front_push -
            wall_gap_slope * std::max(wall_candidates_.depth_low[first + i] - front_deepest, 0.0f);
        if (shares_a_corner |
            (most <= std::max(least_push, std::min({push_mm_[w[0]], push_mm_[w[1]], push_mm_[w[2]]}))))
          continue;
        const WallPush push = least_wall_push(front, corners_of(u, frame));
        for (int k = 0; k < 3; ++k) raise(w[k], push.least, push.enough);
      }
    }
  }
  // Where the cap on each corner stopped the raises of keep_upright (a sliver whose corners'
  // distances disagree), the corners the other way move back instead; in a few sweeps, as moving one
  // back can tip a neighbour over (moving back inside the walk above undoes raises it then redoes). Only
  // triangles marked turning over can be: each is so marked when a corner of it moves back.
  bool moved = false;
  for (int sweep = 0; sweep < 4; ++sweep) {
    moved = false;
    for (const std::uint32_t y : patch_) {
      for (const std::uint32_t t : field_.triangles_around(y)) {
        if ((unsettled_[t] & turning_over) == 0) continue;
        const std::uint32_t* corner = &welded_.indices[3 * std::size_t(t)];
        std::uint32_t first = y;  // each triangle once, from its first corner in the patch
        for (int k = 0; k < 3; ++k)
          if (corner[k] < first && !std::isinf(distance_mm_[corner[k]])) first = corner[k];
        if (first != y) continue;
        const Corners c = corners_of(t, frame);
        float along[3], upright = 1.0f, falling = 0.0f;
        upright_share(c, frame, along, upright);
        for (int k = 0; k < 3; ++k) falling -= std::min(along[k], 0.0f);
        unsettled_[t] = 0;
        if (upright >= 1.0f - wall_gap_slope || !(falling > 0.0f)) continue;
        const float less = (1.0f - wall_gap_slope - upright) / falling;
        for (int k = 0; k < 3; ++k) {
          if (along[k] >= 0.0f) continue;
          push_mm_[c.vertex[k]] = std::max(c.push[k] - less, 0.0f);
          queued_[c.vertex[k]] |= lowered;
          for (const std::uint32_t u : field_.triangles_around(c.vertex[k])) unsettled_[u] = turning_over;
        }
        moved = true;
      }
    }
    if (!moved) break;
  }
  if (moved) {  // the last sweep's marks
    for (const std::uint32_t y : patch_)
      for (const std::uint32_t t : field_.triangles_around(y)) unsettled_[t] = 0;
  }
  // The distance at which the dent's Gaussian gives each vertex its push.
  const float two_sigma2 = 2.0f * dent.sigma_mm * dent.sigma_mm;
  for (const std::uint32_t v : patch_) {
    const bool moved_back = (queued_[v] & lowered) != 0;
    queued_[v] = 0;
    if (push_mm_[v] <= least_push) {
      if (moved_back) distance_mm_[v] = dent_cutoff_sigmas * dent.sigma_mm;
      continue;
    }
    const float distance =
        std::sqrt(two_sigma2 * std::log(dent.depth_mm / std::min(push_mm_[v], dent.depth_mm)));
    if (distance < distance_mm_[v]) {
      distance_mm_[v] = distance, ++walls_;
    } else if (moved_back) {
      distance_mm_[v] = distance;
    }
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
    moved_reach_mm_ = std::max(moved_reach_mm_, glm::length(straight));
    const glm::vec3 toward = length > 0.0f                  ? -gradient_sum_[v] / length
                             : glm::length(straight) > 0.0f ? glm::normalize(straight)
                                                            : glm::vec3(0.0f);
    write(v, glm::vec4(toward, distance_mm_[v]));
    patch_[kept++] = v;
  }
  patch_.resize(kept);
}

}  // namespace palpate
