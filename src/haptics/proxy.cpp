// God-object proxy step: continuous collision of the proxy's path against the BVH, and the point
// nearest the HIP on the side of up to three constraint planes by an exact active-set solve.
#include "palpate/haptics/proxy.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace palpate {
namespace {

// A path can meet one more plane while three are active, so the solve looks at up to four and keeps
// the (at most three) that the minimum rests on.
constexpr int max_candidates = 4;
// Below these the crease line (two planes) or corner point (three) is too ill-conditioned to trust;
// the smaller subsets then carry the answer (the planes are within 0.006 degrees of each other).
constexpr double min_pair_determinant = 1e-8;
constexpr double min_triple_determinant = 1e-6;
constexpr double min_multiplier = -1e-9;  // mm

struct Candidate {
  glm::dvec3 normal;
  double offset;
  std::uint32_t primitive;
  double multiplier;
};

struct Solution {
  bool found = false;
  unsigned mask = 0;        // which candidates the minimum rests on
  glm::dvec3 offset{0.0};   // minimum - HIP
  double multiplier[max_candidates] = {};
};

bool finite(glm::vec3 v) noexcept { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The point x nearest `hip` with normal_i . x >= offset_i for all candidates: a strictly convex
// problem with at most four constraints, so try the subsets of active planes from the smallest up;
// the first whose multipliers are >= 0 and whose point satisfies the other planes is the minimum.
// Subsets of up to three of four candidates, smallest first, as bit masks (listing them beats
// counting bits at run time).
constexpr unsigned subsets_by_size[] = {0b0000, 0b0001, 0b0010, 0b0100, 0b1000, 0b0011, 0b0101, 0b0110,
                                        0b1001, 0b1010, 0b1100, 0b0111, 0b1011, 0b1101, 0b1110};

Solution solve(const Candidate* c, int count, const glm::dvec3& hip, double tolerance) noexcept {
  double violation[max_candidates];  // how far the HIP is behind each plane, mm
  for (int i = 0; i < count; ++i) violation[i] = c[i].offset - glm::dot(c[i].normal, hip);
  const unsigned all = (1u << count) - 1;
  for (const unsigned mask : subsets_by_size) {
    if ((mask & ~all) != 0) continue;
    int index[3] = {};
    int size = 0;
    for (int i = 0; i < count; ++i) {
      if (mask & (1u << i)) index[size++] = i;
    }
    Solution s;
    s.mask = mask;
    if (size == 1) {
      const int i = index[0];
      s.multiplier[i] = violation[i];
      s.offset = violation[i] * c[i].normal;
    } else if (size == 2) {
      const int i = index[0], j = index[1];
      const double cosine = glm::dot(c[i].normal, c[j].normal);
      const double determinant = 1.0 - cosine * cosine;
      if (determinant < min_pair_determinant) continue;
      s.multiplier[i] = (violation[i] - cosine * violation[j]) / determinant;
      s.multiplier[j] = (violation[j] - cosine * violation[i]) / determinant;
      s.offset = s.multiplier[i] * c[i].normal + s.multiplier[j] * c[j].normal;
    } else if (size == 3) {
      const int i = index[0], j = index[1], k = index[2];
      const glm::dvec3 jk = glm::cross(c[j].normal, c[k].normal), ki = glm::cross(c[k].normal, c[i].normal),
                       ij = glm::cross(c[i].normal, c[j].normal);
      const double determinant = glm::dot(c[i].normal, jk);
      if (std::abs(determinant) < min_triple_determinant) continue;
      s.offset = (violation[i] * jk + violation[j] * ki + violation[k] * ij) / determinant;
      s.multiplier[i] = glm::dot(s.offset, jk) / determinant;
      s.multiplier[j] = glm::dot(s.offset, ki) / determinant;
      s.multiplier[k] = glm::dot(s.offset, ij) / determinant;
    }
    bool valid = true;
    for (int i = 0; i < count && valid; ++i) {
      if (mask & (1u << i)) {
        valid = s.multiplier[i] >= min_multiplier;
      } else {
        valid = glm::dot(c[i].normal, s.offset) - violation[i] >= -tolerance;
      }
    }
    if (valid) {
      s.found = true;
      return s;
    }
  }
  return {};
}

// Whether the proxy still lies over every triangle of its crease or corner (within `tolerance` of their
// edges). When it does not, it has followed the planes past the end of the feature into free space.
bool supported(const Bvh& bvh, const Candidate* c, int count, const glm::dvec3& p, double tolerance) noexcept {
  for (int i = 0; i < count; ++i) {
    const Bvh::Triangle& tri = bvh.triangle(c[i].primitive);
    for (int e = 0; e < 3; ++e) {
      const glm::dvec3 a(tri.vertices[std::size_t(e)]), b(tri.vertices[std::size_t((e + 1) % 3)]);
      const glm::dvec3 edge = b - a;
      // Distance of p's projection inside the edge's line, positive toward the triangle.
      if (glm::dot(glm::cross(edge, p - a), c[i].normal) < -tolerance * glm::length(edge)) return false;
    }
  }
  return true;
}

// Whether triangle `b` comes up in front of `face`'s plane (by more than `tolerance`): then the two
// meet in a concave crease and both constrain the proxy; otherwise `b` lies beyond a convex edge.
bool rises_above(const Bvh::Triangle& b, const Candidate& face, double epsilon) noexcept {
  const double surface = face.offset - epsilon;
  for (const glm::vec3& v : b.vertices) {
    if (glm::dot(face.normal, glm::dvec3(v)) - surface > 1e-3 * epsilon) return true;
  }
  return false;
}

}  // namespace

void ProxyState::reset(glm::vec3 p) noexcept {
  position = glm::dvec3(p);
  constraint_count = 0;
  placed = true;
  last_iterations = 0;
}

Contact proxy_step(ProxyState& state, const Bvh& bvh, glm::vec3 hip_mm, const ProxyParams& params) noexcept {
  Contact contact;
  contact.hip = hip_mm;
  if (!finite(hip_mm)) return contact;
  if (!state.placed) state.reset(hip_mm);
  const glm::dvec3 hip(hip_mm);
  const double epsilon = params.surface_epsilon_mm;
  const double tolerance = 1e-3 * epsilon;

  // Warm start from the planes the proxy rested on (sliding on a face then costs one segment), except
  // those whose surface the HIP is now on or in front of: they hold nothing back.
  Candidate c[max_candidates];
  int count = 0;
  for (int i = 0; i < state.constraint_count; ++i) {
    const ProxyConstraint& k = state.constraints[std::size_t(i)];
    if (glm::dot(k.normal, hip) < k.offset - epsilon) c[count++] = {k.normal, k.offset, k.primitive, k.multiplier};
  }
  glm::dvec3 p = state.position;
  std::uint32_t last_primitive = count > 0 ? c[0].primitive : 0;  // for a contact if the cap cuts a search short
  bool last_clamped = false;
  glm::dvec3 last_corner(0.0);  // where the last look past an edge started from

  // Moves p toward `to` until the path is epsilon above the plane of the triangle it ran into (not at
  // all when it starts closer than that): everything before the hit is free, so this never crosses a
  // surface. Returns the triangle's plane.
  const auto stop_before = [&](const BvhHit& hit, const glm::dvec3& to) {
    const Bvh::Triangle& tri = bvh.triangle(hit.primitive);
    const glm::dvec3 v0(tri.vertices[0]), v1(tri.vertices[1]), v2(tri.vertices[2]);
    const glm::dvec3 normal = glm::normalize(glm::cross(v1 - v0, v2 - v0));
    const double plane = glm::dot(normal, v0);
    const double above_from = glm::dot(normal, p) - plane, above_to = glm::dot(normal, to) - plane;
    if (above_from > epsilon && above_from > above_to) {
      p += std::min((above_from - epsilon) / (above_from - above_to), 1.0) * (to - p);
    }
    last_primitive = hit.primitive;
    return Candidate{normal, plane + epsilon, hit.primitive, 0.0};
  };

  int iteration = 0;
  while (iteration < params.max_iterations) {
    ++iteration;
    const Solution s = solve(c, count, hip, tolerance);
    if (!s.found) break;  // degenerate planes (a gap narrower than 2 epsilon): stay put this tick
    int kept = 0;
    for (int i = 0; i < count; ++i) {
      if (s.mask & (1u << i)) {
        c[kept] = c[i];
        c[kept++].multiplier = s.multiplier[i];
      }
    }
    count = kept;
    glm::dvec3 goal = hip + s.offset;
    bool clamped = false;
    glm::dvec3 corner(0.0);
    if (count == 1) {
      // On one face: the nearest point of that triangle (not of its whole plane), so the proxy walks
      // onto an edge or vertex when that is where the surface comes closest to the HIP.
      const Bvh::Triangle& tri = bvh.triangle(c[0].primitive);
      corner = closest_point_on_triangle(hip, glm::dvec3(tri.vertices[0]), glm::dvec3(tri.vertices[1]),
                                         glm::dvec3(tri.vertices[2]));
      const glm::dvec3 lifted = corner + (c[0].offset - glm::dot(c[0].normal, corner)) * c[0].normal;
      const glm::dvec3 step = lifted - goal;
      clamped = glm::dot(step, step) > tolerance * tolerance;
      goal = lifted;
      // The look past the last edge found the same edge or vertex: that is the closest point.
      if (clamped && last_clamped && glm::distance(corner, last_corner) < tolerance) break;
    }
    if (clamped) {
      // The face's nearest point is on its edge: first see what lies toward the HIP from here.
      const BvhHit next = bvh.first_hit(p, hip, Faces::front, tolerance);
      if (!next.hit()) {  // nothing in the way: the HIP is outside and reachable
        p = hip;
        count = 0;
        break;
      }
      if (next.primitive != c[0].primitive) {
        const Candidate face = c[0];
        const Candidate other = stop_before(next, hip);
        if (rises_above(bvh.triangle(next.primitive), face, epsilon)) {
          c[count++] = other;  // a concave crease: both faces hold the proxy
          last_clamped = false;
        } else {
          c[0] = other;  // past a convex edge: the face beyond takes over
          last_clamped = true;
          last_corner = corner;
        }
        continue;
      }
      // Its own face is in the way: walk on it to its nearest point (then look again from there).
    }
    const glm::dvec3 path = goal - p;
    if (glm::dot(path, path) > 1e-24) {  // 1e-12 mm
      const BvhHit hit = bvh.first_hit(p, goal, Faces::front, tolerance);
      if (hit.hit()) {
        c[count++] = stop_before(hit, goal);
        last_clamped = false;
        continue;
      }
      p = goal;
      if (clamped) continue;
    } else if (clamped) {
      break;  // at its face's nearest point, the face itself in the way: as close as it gets
    }
    if (count <= 1) break;  // free at the HIP, or resting inside a face
    if (supported(bvh, c, count, p, epsilon)) break;
    count = 0;  // a crease or corner past the end of its triangles: find the constraints again from here
    last_clamped = false;
  }

  state.position = p;
  state.last_iterations = iteration;
  // Keep at most three planes (the solve keeps no more; a capped tick may end with a fourth).
  const int first = std::max(0, count - 3);
  state.constraint_count = count - first;
  for (int i = first; i < count; ++i) {
    state.constraints[std::size_t(i - first)] = {c[i].normal, c[i].offset, c[i].multiplier, c[i].primitive};
  }

  contact.point = glm::vec3(p);
  const glm::dvec3 spring = p - hip;
  const double depth = glm::length(spring);
  // In contact while a plane holds the proxy back, or while a search the cap cut short left it apart
  // from the HIP (it resumes next tick).
  if (state.constraint_count == 0 && depth <= epsilon) return contact;
  std::uint32_t primary = last_primitive;
  double strongest = -1.0;
  for (int i = 0; i < state.constraint_count; ++i) {
    if (state.constraints[std::size_t(i)].multiplier > strongest) {
      strongest = state.constraints[std::size_t(i)].multiplier;
      primary = state.constraints[std::size_t(i)].primitive;
    }
  }
  bvh.locate(primary, contact.object, contact.triangle);
  if (depth > 0.5 * epsilon) {
    contact.normal = glm::vec3(spring / depth);
  } else {
    const Bvh::Triangle& tri = bvh.triangle(primary);
    contact.normal = glm::vec3(glm::normalize(glm::cross(glm::dvec3(tri.vertices[1]) - glm::dvec3(tri.vertices[0]),
                                                         glm::dvec3(tri.vertices[2]) - glm::dvec3(tri.vertices[0]))));
  }
  contact.depth_mm = float(depth);
  return contact;
}

}  // namespace palpate
