#include "palpate/core/geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>

#include "in_plane.hpp"
#include "palpate/core/error.hpp"

namespace palpate {
namespace {

constexpr float infinity = std::numeric_limits<float>::infinity();

// The front's arrival at C in a plane where it is known at A (da) and B (db), with A at the origin, B at
// (length, 0) and C at `c` (c.y >= 0), `ac` and `bc` from A and B: from the source S that is da from A and
// db from B below AB, straight to C when that line crosses AB between A and B (then `source_out`, where
// given, gets S); else along an edge. Exact for a point source in the plane; the edge paths bound it from
// above.
float planar_update_on_edge(float length, float da, float db, glm::vec2 c, float ac, float bc,
                            glm::vec2* source_out = nullptr) {
  const float along_edges = std::min(da + ac, db + bc);
  if (!(length > 0.0f)) return along_edges;
  const float sx = (da * da - db * db + length * length) / (2.0f * length);
  const float sy2 = da * da - sx * sx;
  if (sy2 < 0.0f) return along_edges;  // no source makes both distances: the front is not planar here
  const float sy = std::sqrt(sy2);
  if (!(sy > 0.0f && c.y > 0.0f)) return along_edges;
  const float x = sx + (c.x - sx) * (sy / (sy + c.y));
  if (x < 0.0f || x > length) return along_edges;
  if (source_out) *source_out = {sx, -sy};
  return std::min(std::sqrt((c.x - sx) * (c.x - sx) + (c.y + sy) * (c.y + sy)), along_edges);
}

// The same for A, B and C anywhere in the plane, the source on the far side of AB from C.
float planar_update(glm::vec2 a, float da, glm::vec2 b, float db, glm::vec2 c) {
  const float length = glm::distance(a, b);
  const glm::vec2 u = length > 0.0f ? (b - a) / length : glm::vec2(1.0f, 0.0f), n(-u.y, u.x);
  return planar_update_on_edge(length, da, db, {glm::dot(c - a, u), std::abs(glm::dot(c - a, n))},
                               glm::distance(a, c), glm::distance(b, c));
}

}  // namespace

GeodesicField::GeodesicField(const Mesh& mesh) : mesh_(mesh) {
  const std::size_t vertices = mesh.vertex_count(), triangles = mesh.indices.size() / 3;
  first_triangle_.assign(vertices + 1, 0);
  for (const std::uint32_t v : mesh.indices) ++first_triangle_[v + 1];
  for (std::size_t v = 0; v < vertices; ++v) first_triangle_[v + 1] += first_triangle_[v];
  vertex_triangles_.resize(mesh.indices.size());
  std::vector<std::uint32_t> filled(first_triangle_.begin(), first_triangle_.end() - 1);
  for (std::size_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) vertex_triangles_[filled[mesh.indices[3 * t + k]]++] = std::uint32_t(t);

  // The triangle across each edge: edges sorted by their corners; an edge of more than two triangles
  // (non-manifold) is left without one.
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> edges;  // low, high, 3t + e
  edges.reserve(mesh.indices.size());
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t p = mesh.indices[3 * t + e], q = mesh.indices[3 * t + (e + 1) % 3];
      edges.emplace_back(std::min(p, q), std::max(p, q), std::uint32_t(3 * t + e));
    }
  }
  std::sort(edges.begin(), edges.end());
  triangle_.resize(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      triangle_[t].corner[k] = mesh.indices[3 * t + k];
      triangle_[t].across[k] = -1;
    }
  }
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i]))
      ++j;
    if (j - i == 2) {
      for (const auto& [one, other] : {std::pair(i, i + 1), std::pair(i + 1, i)}) {
        const std::uint32_t at = std::get<2>(edges[one]), beyond = std::get<2>(edges[other]);
        triangle_[at / 3].across[at % 3] = std::int32_t(beyond / 3);
        triangle_[at / 3].across_edge[at % 3] = std::uint8_t(beyond % 3);
      }
    }
    i = j;
  }

  for (std::size_t t = 0; t < triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 pa = mesh.positions_mm[mesh.indices[3 * t + (k + 1) % 3]],
                      pb = mesh.positions_mm[mesh.indices[3 * t + (k + 2) % 3]];
      const float length = glm::distance(pa, pb);
      triangle_[t].layout[k] = {length, length > 0.0f
                                            ? in_plane(pa, pb, mesh.positions_mm[mesh.indices[3 * t + k]])
                                            : glm::vec2(0.0f)};
    }
  }
  // Shortest paths bend only at vertices whose corners' angles pass 2 pi (saddles) and on boundaries,
  // and there only by pi or more on either side: each corner's angle, and where its sector starts going
  // round its vertex (from the edge to the next corner), for the vertices whose triangles close round them.
  vertex_.assign(vertices, VertexState{});
  corner_angle_.assign(mesh.indices.size(), 0.0f);
  fan_start_.assign(mesh.indices.size(), 0.0f);
  fan_angle_.assign(vertices, 0.0f);
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 corner = mesh.positions_mm[mesh.indices[3 * t + k]],
                       to_a = glm::dvec3(mesh.positions_mm[mesh.indices[3 * t + (k + 1) % 3]]) - corner,
                       to_b = glm::dvec3(mesh.positions_mm[mesh.indices[3 * t + (k + 2) % 3]]) - corner;
      const double lengths = glm::length(to_a) * glm::length(to_b);
      if (lengths > 0.0)
        corner_angle_[3 * t + k] = float(std::acos(std::clamp(glm::dot(to_a, to_b) / lengths, -1.0, 1.0)));
      fan_angle_[mesh.indices[3 * t + k]] += corner_angle_[3 * t + k];
      if (triangle_[t].across[k] < 0) {
        vertex_[mesh.indices[3 * t + k]].pseudo_source = true;
        vertex_[mesh.indices[3 * t + (k + 1) % 3]].pseudo_source = true;
      }
    }
  }
  const auto corner_of = [&](std::uint32_t t, std::uint32_t v) {
    const std::uint32_t* c = &mesh.indices[3 * std::size_t(t)];
    return c[0] == v ? 0 : c[1] == v ? 1 : 2;
  };
  for (std::uint32_t v = 0; v < vertices; ++v) {
    if (fan_angle_[v] > 2.0 * std::numbers::pi * (1.0 + 1e-6)) vertex_[v].pseudo_source = true;
    const std::span<const std::uint32_t> fan = triangles_around(v);
    std::size_t walked = 0;
    float at = 0.0f;
    for (std::uint32_t t = fan.empty() ? 0 : fan[0]; walked < fan.size(); ++walked) {
      const int k = corner_of(t, v);
      fan_start_[3 * std::size_t(t) + k] = at;
      at += corner_angle_[3 * std::size_t(t) + k];
      const std::int32_t next = triangle_[t].across[(k + 2) % 3];  // across the edge from k + 2 to k
      if (next < 0 || mesh.indices[3 * std::size_t(next) + (corner_of(std::uint32_t(next), v) + 1) % 3] !=
                          mesh.indices[3 * std::size_t(t) + (k + 2) % 3])
        break;
      t = std::uint32_t(next);
      if (t == fan[0]) {
        ++walked;
        break;
      }
    }
    if (walked != fan.size()) fan_angle_[v] = std::numeric_limits<float>::quiet_NaN();  // not a closed fan
  }
  queue_.resize(std::max<std::size_t>(vertices, 1));
  heap_.reserve(vertices);
  touched_.reserve(vertices);
  reached_.reserve(vertices);
}

float GeodesicField::distance_mm(std::uint32_t vertex) const noexcept {
  return vertex < vertex_.size() ? vertex_[vertex].distance : infinity;
}

void GeodesicField::compute(std::uint32_t triangle, glm::vec3 point_mm, float radius_mm) {
  compute(triangle, point_mm, radius_mm, Reach{});
}

void GeodesicField::compute(std::uint32_t triangle, glm::vec3 point_mm, float radius_mm, Reach reach) {
  if (triangle >= triangle_.size()) {
    throw Error("GeodesicField: triangle " + std::to_string(triangle) + " of " +
                std::to_string(triangle_.size()));
  }
  for (const std::uint32_t v : touched_) {
    VertexState& state = vertex_[v];
    state = VertexState{.pseudo_source = state.pseudo_source};
  }
  touched_.clear();
  heap_.clear();
  reached_.clear();
  exact_mm_ = std::min(reach.exact_mm, radius_mm);
  window_budget_ = reach.window_budget;
  light(triangle, point_mm);
  // The march starts from the vertices the windows reached: fixed within exact_mm, beyond it at the
  // length of a real path, which the march may shorten.
  for (const std::uint32_t v : touched_) {
    if (vertex_[v].distance <= exact_mm_) {
      vertex_[v].exact = vertex_[v].alive = true;
      reached_.push_back(v);
    } else {
      vertex_[v].heap_position = std::int32_t(heap_.size());
      heap_.push_back(v);
      sift_up(heap_.size() - 1);
    }
  }
  std::sort(reached_.begin(), reached_.end(),
            [&](std::uint32_t a, std::uint32_t b) { return vertex_[a].distance < vertex_[b].distance; });
  for (const std::uint32_t u : reached_) {
    for (const std::uint32_t t : triangles_around(u)) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t c = triangle_[t].corner[k];
        if (!vertex_[c].alive) update(c, t);
      }
    }
  }
  while (!heap_.empty()) {
    const std::uint32_t u = pop();
    vertex_[u].alive = true;
    if (vertex_[u].distance > radius_mm) break;
    reached_.push_back(u);
    for (std::uint32_t i = first_triangle_[u]; i < first_triangle_[u + 1]; ++i) {
      const std::uint32_t t = vertex_triangles_[i];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t c = triangle_[t].corner[k];
        if (!vertex_[c].alive) update(c, t);
      }
    }
  }
  correct(reach.second_look_mm);
}

// The march fixes a vertex from the triangles whose other corners were fixed before it. Where the front
// reaches a vertex through a triangle with a corner fixed after it (beyond an obtuse corner, across a
// long thin triangle), the march takes a path along an edge instead, up to several percent long, and
// the error spreads onward. Where a triangle's far corner across ab was not fixed yet, its source could
// not be checked (unless_a_false_source) and may lie too near. So, once all are fixed, one pass in the
// order they were reached updates again, from all its triangles, each vertex that came along an edge or
// next to one this pass lowered by more than 0.1%, and computes afresh each whose source went unchecked
// (carrying on changes under 0.1% cost a third more at sigma 8 mm and changed no measured error). A
// vertex that changes by more than 1% sends its neighbours, the ones the pass has left behind too, to a
// queue worked until no vertex changes by 1%. On a jittered plane the mean error fell from 0.07 to
// 0.003 mm. Against CGAL's exact paths (60 contacts on each of four cortices, sigma 2, 4, 8 mm) the pass
// alone brought the largest weight error from 0.038 to 0.022 of p on the Colin27 brain at sigma 2 mm and
// from 0.15 to 0.018 on the coarse SPM12 cortex; the fresh look at unchecked sources and the queue then
// cut the contacts over 0.03 of p from 9 to 7 (Colin27: 0.047 to 0.028 at sigma 2 mm, 0.041 to 0.032
// at sigma 4 mm), for 8-15% of the march (docs/design.md). The pass leaves the vertices beyond
// `within_mm` as the march left them, but for the queue: the edge arrivals are as common far out as
// near, and the band of vertices after them that the pass lowers widens with the distance.
void GeodesicField::correct(float within_mm) {
  std::size_t head = 0, count = 0;
  const auto enqueue_neighbours = [&](std::uint32_t v) {
    for (const std::uint32_t t : triangles_around(v)) {
      const std::uint32_t* corners = triangle_[t].corner;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t n = corners[k];
        if (n == v || !vertex_[n].alive || vertex_[n].exact || vertex_[n].queued == 2) continue;
        vertex_[n].queued = 2;
        queue_[(head + count++) % queue_.size()] = n;
      }
    }
  };
  for (const std::uint32_t v : reached_) {
    if ((!vertex_[v].along_edge && !vertex_[v].unchecked && !vertex_[v].queued) || vertex_[v].exact ||
        vertex_[v].distance > within_mm)
      continue;
    const bool carried_on = vertex_[v].along_edge || vertex_[v].queued;
    const float before = vertex_[v].distance, after = update_again(v);
    if (std::abs(after - before) > before * 1e-2f) enqueue_neighbours(v);
    if (carried_on && std::abs(after - before) > before * 1e-3f) {
      for (const std::uint32_t t : triangles_around(v)) {
        const std::uint32_t* corners = triangle_[t].corner;
        for (int k = 0; k < 3; ++k)
          vertex_[corners[k]].queued = std::max<std::uint8_t>(vertex_[corners[k]].queued, 1);
      }
    }
  }
  while (count > 0) {
    const std::uint32_t v = queue_[head];
    head = (head + 1) % queue_.size(), --count;
    vertex_[v].queued = 0;
    const float before = vertex_[v].distance, after = update_again(v);
    if (std::abs(after - before) > before * 1e-2f) enqueue_neighbours(v);
  }
}

// A vertex's distance from all its triangles, now that its neighbours are known: lowered, or afresh where
// the march could not check its source.
float GeodesicField::update_again(std::uint32_t v) {
  // Afresh where unchecked: the update checks its source only below the distance it has.
  if (vertex_[v].unchecked) vertex_[v].distance = infinity;
  vertex_[v].unchecked = false;
  float best = vertex_[v].distance;
  for (const std::uint32_t t : triangles_around(v)) {
    const std::uint32_t* corners = triangle_[t].corner;
    const int k = corners[0] == v ? 0 : corners[1] == v ? 1 : 2;
    best = std::min(best, along_edges(t, k));
    if (vertex_[corners[(k + 1) % 3]].alive && vertex_[corners[(k + 2) % 3]].alive)
      best = std::min(best, unfolded_update(t, k));
  }
  return vertex_[v].distance = best;
}

// The arrival at the triangle's corner k along an edge from one of the other two that is fixed.
float GeodesicField::along_edges(std::uint32_t triangle, int k) const {
  const std::uint32_t* corners = triangle_[triangle].corner;
  const std::uint32_t a = corners[(k + 1) % 3], b = corners[(k + 2) % 3];
  const Layout* layout = triangle_[triangle].layout;
  float along = infinity;
  if (vertex_[a].alive) along = std::min(along, vertex_[a].distance + layout[(k + 2) % 3].edge_mm);
  if (vertex_[b].alive) along = std::min(along, vertex_[b].distance + layout[(k + 1) % 3].edge_mm);
  return along;
}

void GeodesicField::update(std::uint32_t c, std::uint32_t triangle) {
  const std::uint32_t* corners = triangle_[triangle].corner;
  const int k = corners[0] == c ? 0 : corners[1] == c ? 1 : 2;
  const std::uint32_t a = corners[(k + 1) % 3], b = corners[(k + 2) % 3];
  const float along_edge = along_edges(triangle, k);
  bool unchecked = false;
  const float through =
      vertex_[a].alive && vertex_[b].alive ? unfolded_update(triangle, k, &unchecked) : infinity;
  if (std::min(along_edge, through) < vertex_[c].distance)
    vertex_[c].unchecked = unchecked && through < along_edge;
  push_or_lower(c, std::min(along_edge, through), !(through < along_edge));
}

// A triangle's source, placed from its corners a and b, is false where the vertex x across ab, fixed
// before them, lies farther than the straight line from that source through the unfolded pair: a real
// source would reach x no later. Then a and b were reached from either side of a saddle vertex or a
// fold (the paths to them bend around it), and the source lies too near: the update came out up to 8%
// short of CGAL's exact path on the Colin27 brain. The front then comes through the pairs (a, x) and
// (x, b) laid out beyond ab, or along the edges. 2% leaves the bends of a curved surface alone (with
// no margin the error grew fourfold); on Colin27 the contacts whose weight error passes 0.03 of p fell
// from 2 / 4 / 3 in 60 to 1 / 2 / 1 at sigma 2 / 4 / 8 mm (docs/design.md). It costs about 7% of the
// march, checked only where the update would lower the vertex.
float GeodesicField::unless_a_false_source(std::uint32_t triangle, int k, glm::vec2 source, glm::vec2 c2,
                                           float distance, bool* unchecked) const {
  const std::uint32_t* corners = triangle_[triangle].corner;
  const std::uint32_t a = corners[(k + 1) % 3], b = corners[(k + 2) % 3];
  const std::int32_t beyond = triangle_[triangle].across[(k + 1) % 3];  // the edge from a to b
  if (beyond < 0) return distance;
  const std::uint32_t* far = triangle_[beyond].corner;
  const int j = far[0] != a && far[0] != b ? 0 : far[1] != a && far[1] != b ? 1 : 2;
  const std::uint32_t x = far[j];
  if (!vertex_[x].alive) {
    if (unchecked) *unchecked = true;
    return distance;
  }
  // x as laid out in its own triangle, over the same edge from a to b or from b to a, mirrored below it.
  const Layout& at_x = triangle_[beyond].layout[j];
  const glm::vec2 a2(0.0f), b2(triangle_[triangle].layout[k].edge_mm, 0.0f),
      x2 = far[(j + 1) % 3] == a ? glm::vec2(at_x.corner.x, -at_x.corner.y)
                                 : glm::vec2(b2.x - at_x.corner.x, -at_x.corner.y);
  if (!(vertex_[x].distance > glm::distance(source, x2) * 1.02f)) return distance;
  return std::min({vertex_[a].distance + glm::length(c2), vertex_[b].distance + glm::distance(b2, c2),
                   planar_update(a2, vertex_[a].distance, x2, vertex_[x].distance, c2),
                   planar_update(x2, vertex_[x].distance, b2, vertex_[b].distance, c2)});
}

GeodesicField::Across GeodesicField::across(std::uint32_t triangle, std::uint32_t p, std::uint32_t q) const {
  const std::uint32_t* corners = triangle_[triangle].corner;
  int edge = -1;
  for (int e = 0; e < 3; ++e) {
    const std::uint32_t u = corners[e], v = corners[(e + 1) % 3];
    if ((u == p && v == q) || (u == q && v == p)) edge = e;
  }
  const std::int32_t next = edge < 0 ? -1 : triangle_[triangle].across[edge];
  if (next < 0) return {-1, 0, 0.0f, 0.0f};
  // The edge is (e, e + 1) of the triangle beyond: the corner is e + 2, its edges the ones across from e + 1
  // and e.
  const Triangle& far = triangle_[next];
  const int e = triangle_[triangle].across_edge[edge];
  const float from_first = far.layout[(e + 1) % 3].edge_mm, from_second = far.layout[e].edge_mm;
  return far.corner[e] == p ? Across{next, far.corner[(e + 2) % 3], from_first, from_second}
                            : Across{next, far.corner[(e + 2) % 3], from_second, from_first};
}

// The triangle's own update from the source its corners a and b place; at an obtuse corner c, Kimmel and
// Sethian's unfolding: the triangles across ab are laid into the plane, one after another, until a corner d'
// splits the corner at c into two acute ones; the front then arrives at c from (a, d') and (d', b), through
// the strip, not along an edge. Up to `max_unfoldings` triangles.
float GeodesicField::unfolded_update(std::uint32_t triangle, int k, bool* unchecked) const {
  constexpr int max_unfoldings = 6;
  const std::uint32_t* corners = triangle_[triangle].corner;
  const std::uint32_t c = corners[k], a = corners[(k + 1) % 3], b = corners[(k + 2) % 3];
  const Layout* layout = triangle_[triangle].layout;
  const glm::vec2 a2(0.0f), b2(layout[k].edge_mm, 0.0f), c2 = layout[k].corner;
  glm::vec2 source(std::numeric_limits<float>::quiet_NaN());
  float best = planar_update_on_edge(layout[k].edge_mm, vertex_[a].distance, vertex_[b].distance, c2,
                                     layout[(k + 2) % 3].edge_mm, layout[(k + 1) % 3].edge_mm, &source);
  if (source.x == source.x && best < vertex_[c].distance)  // else it changes nothing: spare the check
    best = unless_a_false_source(triangle, k, source, c2, best, unchecked);
  if (glm::dot(a2 - c2, b2 - c2) >= 0.0f) return best;  // not obtuse at c

  // The strip: the edge (p, q) just crossed, laid out at (p2, q2), the triangle beyond it, and the
  // point of the last triangle off that edge (to put the next one on the other side).
  std::uint32_t p = a, q = b, current = triangle;
  glm::vec2 p2 = a2, q2 = b2, behind = c2;
  for (int level = 0; level < max_unfoldings; ++level) {
    const Across beyond = across(current, p, q);
    if (beyond.triangle < 0) return best;
    const std::uint32_t d = beyond.corner;
    // d laid out across (p2, q2), on the side away from `behind`.
    const glm::vec2 edge2 = q2 - p2;
    const float length = glm::length(edge2);
    if (!(length > 0.0f)) return best;
    const glm::vec2 u = edge2 / length, n(-u.y, u.x);
    const float dp = beyond.from_p_mm, dq = beyond.from_q_mm;
    const float x = (dp * dp - dq * dq + length * length) / (2.0f * length);
    const float side = glm::dot(behind - p2, n) >= 0.0f ? -1.0f : 1.0f;
    const glm::vec2 d2 = p2 + u * x + n * (side * std::sqrt(std::max(dp * dp - x * x, 0.0f)));
    const bool acute_to_a = glm::dot(a2 - c2, d2 - c2) > 0.0f, acute_to_b = glm::dot(b2 - c2, d2 - c2) > 0.0f;
    if (acute_to_a && acute_to_b) {  // d' splits the obtuse corner
      if (!vertex_[d].alive) return best;
      best = std::min(best, planar_update(a2, vertex_[a].distance, d2, vertex_[d].distance, c2));
      return std::min(best, planar_update(d2, vertex_[d].distance, b2, vertex_[b].distance, c2));
    }
    // Onward across the edge of the new triangle on the section's side: d' leaning toward b (not acute
    // to a) leaves the section between a's side and d', so across (p, d); else across (d, q). The next
    // triangle lies away from the new triangle's third corner.
    if (!acute_to_a) {
      behind = q2;
      q = d, q2 = d2;
    } else {
      behind = p2;
      p = d, p2 = d2;
    }
    current = std::uint32_t(beyond.triangle);
  }
  return best;
}

void GeodesicField::push_or_lower(std::uint32_t vertex, float distance, bool along_edge) {
  if (!(distance < vertex_[vertex].distance)) return;
  if (vertex_[vertex].distance == infinity && vertex_[vertex].heap_position < 0) touched_.push_back(vertex);
  vertex_[vertex].distance = distance;
  vertex_[vertex].along_edge = along_edge;
  if (vertex_[vertex].heap_position < 0) {
    vertex_[vertex].heap_position = std::int32_t(heap_.size());
    heap_.push_back(vertex);
  }
  sift_up(std::size_t(vertex_[vertex].heap_position));
}

std::uint32_t GeodesicField::pop() {
  const std::uint32_t top = heap_.front();
  vertex_[top].heap_position = -1;
  heap_.front() = heap_.back();
  heap_.pop_back();
  if (!heap_.empty()) {
    vertex_[heap_.front()].heap_position = 0;
    sift_down(0);
  }
  return top;
}

void GeodesicField::sift_up(std::size_t at) {
  while (at > 0) {
    const std::size_t parent = (at - 1) / 2;
    if (!(vertex_[heap_[at]].distance < vertex_[heap_[parent]].distance)) break;
    std::swap(heap_[at], heap_[parent]);
    vertex_[heap_[at]].heap_position = std::int32_t(at);
    vertex_[heap_[parent]].heap_position = std::int32_t(parent);
    at = parent;
  }
}

void GeodesicField::sift_down(std::size_t at) {
  for (;;) {
    const std::size_t left = 2 * at + 1, right = left + 1;
    std::size_t least = at;
    if (left < heap_.size() && vertex_[heap_[left]].distance < vertex_[heap_[least]].distance) least = left;
    if (right < heap_.size() && vertex_[heap_[right]].distance < vertex_[heap_[least]].distance)
      least = right;
    if (least == at) return;
    std::swap(heap_[at], heap_[least]);
    vertex_[heap_[at]].heap_position = std::int32_t(at);
    vertex_[heap_[least]].heap_position = std::int32_t(least);
    at = least;
  }
}

}  // namespace palpate
