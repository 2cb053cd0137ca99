#include "core/edge_flips.hpp"

#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "palpate/core/error.hpp"

namespace palpate::detail {
namespace {

// Corner table (Rossignac): corner c is vertex indices[c] of triangle c / 3; the edge facing c runs
// from corner next(c) to corner prev(c); opposite[c] is the corner facing the same edge in the other
// triangle.
std::uint32_t next(std::uint32_t c) {
  return c % 3 == 2 ? c - 2 : c + 1;
}
std::uint32_t prev(std::uint32_t c) {
  return c % 3 == 0 ? c + 2 : c - 1;
}

}  // namespace

std::vector<std::uint32_t> opposite_corners(const Mesh& mesh) {
  const auto corners = static_cast<std::uint32_t>(mesh.indices.size());
  const std::vector<std::uint32_t>& v = mesh.indices;
  // Bucket the corners by the vertex their facing edge starts from (a counting sort: linear time).
  std::vector<std::uint32_t> start(mesh.vertex_count() + 1, 0);
  for (std::uint32_t c = 0; c < corners; ++c) ++start[v[next(c)] + 1];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> bucket(corners);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t c = 0; c < corners; ++c) bucket[fill[v[next(c)]]++] = c;

  std::vector<std::uint32_t> opposite(corners);
  for (std::uint32_t c = 0; c < corners; ++c) {
    const std::uint32_t from = v[next(c)], to = v[prev(c)];
    bool found = false;
    for (std::uint32_t i = start[to]; i < start[to + 1] && !found; ++i) {
      if (v[prev(bucket[i])] == from) {
        opposite[c] = bucket[i];
        found = true;
      }
    }
    if (!found) {
      throw Error("opposite_corners: edge " + std::to_string(from) + "-" + std::to_string(to) +
                  " has no opposite triangle; the mesh must be closed and consistently oriented");
    }
  }
  return opposite;
}

namespace {

// Cotangent of the angle at `apex` between the directions to a and b.
double cotangent(glm::dvec3 apex, glm::dvec3 a, glm::dvec3 b) {
  const glm::dvec3 e1 = a - apex, e2 = b - apex;
  return glm::dot(e1, e2) / glm::length(glm::cross(e1, e2));
}

glm::dvec3 unit_normal(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  return glm::normalize(glm::cross(b - a, c - a));
}

// True when (a, b, c) turns counter-clockwise seen from the centre, by a margin relative to its size so
// that float rounding of the stored positions cannot change the verdict.
bool faces_away(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const double volume = glm::dot(a, glm::cross(b, c));
  return volume > 0.0 && volume * volume > 1e-18 * glm::dot(a, a) * glm::dot(b, b) * glm::dot(c, c);
}

}  // namespace

std::size_t flip_toward_delaunay(Mesh& mesh, std::vector<std::uint32_t>& opposite, glm::dvec3 centre,
                                 double max_fold_rad) {
  std::vector<std::uint32_t>& v = mesh.indices;
  const double min_cos = std::cos(max_fold_rad);
  const auto at = [&](std::uint32_t vertex) { return glm::dvec3(mesh.positions_mm[vertex]) - centre; };

  std::vector<std::uint32_t> pending;
  pending.reserve(v.size());
  for (std::uint32_t c = 0; c < v.size(); ++c) {
    if (c < opposite[c]) pending.push_back(c);
  }
  // Each flip strictly lowers the sum of the cotangent criterion over a planar region; the cap only
  // guards against a cycle on the non-planar surface.
  const std::size_t max_flips = 4 * v.size();
  std::size_t flips = 0;
  while (!pending.empty() && flips < max_flips) {
    const std::uint32_t c = pending.back();
    pending.pop_back();
    const std::uint32_t o = opposite[c];
    const std::uint32_t n1 = next(c), p1 = prev(c), n2 = next(o), p2 = prev(o);
    // Triangle (vc, va, vb) and its neighbour (vo, vb, va) across the edge va-vb.
    const glm::dvec3 pc = at(v[c]), pa = at(v[n1]), pb = at(v[p1]), po = at(v[o]);
    // Two acute opposite angles sum to less than pi: the common case, decided without a square root.
    if (glm::dot(pa - pc, pb - pc) >= 0.0 && glm::dot(pb - po, pa - po) >= 0.0) continue;
    if (cotangent(pc, pa, pb) + cotangent(po, pb, pa) >= -1e-9) continue;  // already Delaunay
    if (glm::dot(unit_normal(pc, pa, pb), unit_normal(po, pb, pa)) < min_cos) continue;
    if (!faces_away(pc, pa, po) || !faces_away(po, pb, pc)) continue;
    if (glm::dot(unit_normal(pc, pa, po), unit_normal(po, pb, pc)) < min_cos) continue;

    // Replace the diagonal va-vb by vc-vo: triangles (vc, va, vo) and (vo, vb, vc).
    const std::uint32_t vc = v[c], va = v[n1], vb = v[p1], vo = v[o];
    const std::uint32_t across_a_o = opposite[n2];  // edge va -> vo, faced by n2 before the flip
    const std::uint32_t across_b_c = opposite[n1];  // edge vb -> vc, faced by n1 before the flip
    v[c] = vc, v[n1] = va, v[p1] = vo;
    v[o] = vo, v[n2] = vb, v[p2] = vc;
    opposite[c] = across_a_o, opposite[across_a_o] = c;
    opposite[o] = across_b_c, opposite[across_b_c] = o;
    opposite[n1] = n2, opposite[n2] = n1;
    ++flips;
    pending.insert(pending.end(), {c, o, p1, p2});
  }
  return flips;
}

}  // namespace palpate::detail
