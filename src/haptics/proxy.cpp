// God-object proxy step: continuous collision of the proxy's path against the BVH; on one face, a walk
// to the triangle's nearest point and on over the face across its edge; on two or three (concave
// creases and corners), the point nearest the HIP on the free side of their planes; at a vertex, the
// point of the faces round it nearest the HIP.
#include "palpate/haptics/proxy.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "palpate/core/finite.hpp"

namespace palpate {
namespace {

// How near the proxy a face must pass, in surface epsilons, to count as one it touches (it floats one
// epsilon above the planes it rests on; where they meet at a sharp angle, a little more).
constexpr double near_reach = 10.0;

// A path can meet one more plane while three are active, so the solve looks at up to four and keeps
// the (at most three) that the minimum rests on.
constexpr int max_candidates = 4;
// Below these the crease line (two planes) or corner point (three) is too ill-conditioned to trust;
// the smaller subsets then carry the answer (the planes are within 0.006 degrees of each other).
constexpr double min_pair_determinant = 1e-8;
constexpr double min_triple_determinant = 1e-6;
constexpr double min_multiplier = -1e-9;  // mm

struct Candidate {
  glm::dvec3 normal;  // unit, outward
  double offset;      // normal . x >= offset: the face's plane raised by the surface epsilon
  std::uint32_t primitive;
  double multiplier;
};

struct Solution {
  bool found = false;
  unsigned mask = 0;      // which candidates the minimum rests on
  glm::dvec3 point{0.0};  // the minimum
  double multiplier[max_candidates] = {};
};

// Subsets of up to three of four candidates, smallest first, as bit masks (listing them beats
// counting bits at run time).
constexpr unsigned subsets_by_size[] = {0b0000, 0b0001, 0b0010, 0b0100, 0b1000, 0b0011, 0b0101, 0b0110,
                                        0b1001, 0b1010, 0b1100, 0b0111, 0b1011, 0b1101, 0b1110};

// The point nearest `hip` on the free side of every candidate's plane: a strictly convex problem with
// at most four constraints, so try the subsets of planes it may rest on from the smallest up; the
// first whose multipliers are >= 0 (the HIP pushes into each) and whose point is on the free side of
// the others is the minimum (an exact active-set solve).
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
    s.point = hip;
    if (size == 1) {
      const int i = index[0];
      s.multiplier[i] = violation[i];
      s.point += violation[i] * c[i].normal;
    } else if (size == 2) {
      const int i = index[0], j = index[1];
      const double cosine = glm::dot(c[i].normal, c[j].normal);
      const double determinant = 1.0 - cosine * cosine;
      if (determinant < min_pair_determinant) continue;
      s.multiplier[i] = (violation[i] - cosine * violation[j]) / determinant;
      s.multiplier[j] = (violation[j] - cosine * violation[i]) / determinant;
      s.point += s.multiplier[i] * c[i].normal + s.multiplier[j] * c[j].normal;
    } else if (size == 3) {
      const int i = index[0], j = index[1], k = index[2];
      const glm::dvec3 jk = glm::cross(c[j].normal, c[k].normal), ki = glm::cross(c[k].normal, c[i].normal),
                       ij = glm::cross(c[i].normal, c[j].normal);
      const double determinant = glm::dot(c[i].normal, jk);
      if (std::abs(determinant) < min_triple_determinant) continue;
      const glm::dvec3 offset = (violation[i] * jk + violation[j] * ki + violation[k] * ij) / determinant;
      s.multiplier[i] = glm::dot(offset, jk) / determinant;
      s.multiplier[j] = glm::dot(offset, ki) / determinant;
      s.multiplier[k] = glm::dot(offset, ij) / determinant;
      s.point += offset;
    }
    bool valid = true;
    for (int i = 0; i < count && valid; ++i) {
      if (mask & (1u << i)) {
        valid = s.multiplier[i] >= min_multiplier;
      } else {
        valid = glm::dot(c[i].normal, s.point) - c[i].offset >= -tolerance;
      }
    }
    if (valid) {
      s.found = true;
      return s;
    }
  }
  return {};
}

// Whether the proxy still lies over every triangle it rests on (within `tolerance` of their edges).
// When it does not, it has followed their planes past the end of the triangles into free space.
bool supported(const Bvh& bvh, const Candidate* c, int count, const glm::dvec3& p,
               double tolerance) noexcept {
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

// The plane of a triangle, raised by the surface epsilon: a constraint.
Candidate resting_on(const Bvh& bvh, std::uint32_t primitive, double epsilon) noexcept {
  const Bvh::Triangle& tri = bvh.triangle(primitive);
  const glm::dvec3 v0(tri.vertices[0]), v1(tri.vertices[1]), v2(tri.vertices[2]);
  const glm::dvec3 normal = glm::normalize(glm::cross(v1 - v0, v2 - v0));
  return {normal, glm::dot(normal, v0) + epsilon, primitive, 0.0};
}

// The faces round a vertex the search looks at together (the phantom brain's vertices have up to 12).
constexpr std::size_t max_faces_round_vertex = 16;

// A search that reaches a vertex with the HIP behind the surface there: the point of the faces round
// the vertex nearest the HIP is where the proxy rests, lifted by the surface epsilon over the face it
// lies on, or in a valley between two faces where their raised planes meet. (On their far edges too: a
// face beyond that comes nearer is found by the faces-near query that follows a rest on an edge or a
// corner.) Going round those faces one at a time took the search 10 steps a tick at a vertex of a
// sulcus's floor of the phantom brain (docs/design.md, "tenth step"). False when the faces do not
// close round the vertex or the HIP is not behind each plane it would rest on; otherwise `c` and
// `count` hold those planes, `point` where it rests, and `inside_face` whether that is inside a face
// (not on an edge or a corner, where a face of something else that it touches may come nearer).
bool rest_round_vertex(const Bvh& bvh, std::uint32_t face, const glm::dvec3& vertex, const glm::dvec3& hip,
                       double epsilon, double tolerance, Candidate* c, int& count, glm::dvec3& point,
                       bool& inside_face) noexcept {
  std::array<std::uint32_t, max_faces_round_vertex> around;
  const std::size_t faces = bvh.faces_around(face, vertex, around);
  if (faces < 3) return false;
  // Each face's corners from the vertex round (the vertex, then the corner it shares with the next face
  // round, then the one it shares with the one before).
  const auto corners = [&](std::size_t i) {
    const auto& v = bvh.triangle(around[i % faces]).vertices;
    const std::size_t at = glm::dvec3(v[0]) == vertex ? 0 : glm::dvec3(v[1]) == vertex ? 1 : 2;
    return std::array<glm::dvec3, 3>{vertex, glm::dvec3(v[(at + 1) % 3]), glm::dvec3(v[(at + 2) % 3])};
  };
  std::size_t nearest_face = faces;
  TriangleFeature on = TriangleFeature::a;
  double nearest2 = 0.0;
  for (std::size_t i = 0; i < faces; ++i) {
    const auto v = corners(i);
    TriangleFeature feature;
    const glm::dvec3 q = closest_point_on_triangle(hip, v[0], v[1], v[2], feature);
    const double distance2 = glm::dot(q - hip, q - hip);
    if (nearest_face == faces || distance2 < nearest2) {
      nearest_face = i;
      nearest2 = distance2;
      on = feature;
      point = q;
    }
  }
  // Over the face it lies on (at the vertex, the face it is reached on: the first of the nearest).
  c[0] = resting_on(bvh, around[nearest_face], epsilon);
  count = 1;
  if (on == TriangleFeature::ab || on == TriangleFeature::ac) {
    // On the edge it shares with the next face round (ab) or the one before (ac): a valley when the
    // other face's far corner lies in front of this one's plane.
    const std::size_t other = on == TriangleFeature::ab ? nearest_face + 1 : nearest_face + faces - 1;
    const glm::dvec3 far = corners(other)[on == TriangleFeature::ab ? 1 : 2];
    if (glm::dot(c[0].normal, far - vertex) > 0.0) {
      c[1] = resting_on(bvh, around[other % faces], epsilon);
      count = 2;
    }
  }
  const glm::dvec3 lifted = point + (c[0].offset - glm::dot(c[0].normal, point)) * c[0].normal;
  const Solution s = solve(c, count, hip, tolerance);
  // The HIP must be behind every plane it rests on, or the spring would pull it into the surface.
  if (!s.found || s.mask != (1u << count) - 1) return false;
  for (int i = 0; i < count; ++i) c[i].multiplier = s.multiplier[i];
  point = count == 2 ? s.point : lifted;
  inside_face = on == TriangleFeature::face;
  return true;
}

// The corner the faces `c` all share, bit for bit: false when they share none.
bool shared_corner(const Bvh& bvh, const Candidate* c, int count, glm::dvec3& corner) noexcept {
  for (const glm::vec3& v : bvh.triangle(c[0].primitive).vertices) {
    if (std::all_of(c + 1, c + count, [&](const Candidate& k) {
          const auto& w = bvh.triangle(k.primitive).vertices;
          return w[0] == v || w[1] == v || w[2] == v;
        })) {
      corner = glm::dvec3(v);
      return true;
    }
  }
  return false;
}

// The proxy's neighbourhood in the BVH: a box 0.7 of its face's sizes either side (0.26 µs at the
// median and 1.5 µs at p99 at 10 M triangles, between ticks). Its casts then test the 6-14
// leaves listed there side by side instead of walking the tree's chain of dependent box tests
// (docs/design.md, "The haptic tick's memory and time"). Smaller boxes gather more often and larger
// ones list more leaves: 0.65-0.8 measured best, 0.3 and 1.8 worse.
constexpr double neighbourhood_faces = 0.7;
constexpr double min_neighbourhood_mm = 0.05;
// Gathered again between ticks (proxy_prepare) once the proxy is a quarter of the box's half-width
// from its centre, so that a tick's motion keeps it inside (25 um on sphere-slide, a third of the
// half-width at 10 M triangles, where it is gathered nearly every tick); within a tick only once it
// has left the box. A gather between ticks also prefetches the leaves' triangles, which the next
// tick's searches and walks read: 10 M p99 1.20 against 1.39-1.54 us (docs/design.md, eighth step).
constexpr double regather_between_ticks = 0.25;
constexpr double regather_in_tick = 1.0;

// A free proxy (`face` no_neighbour) keeps one too, sized by the tree's typical triangle, so that the
// tick in which it meets the surface casts among leaves: from the root, that tick's two casts read
// parts of the tree untouched since the last contact, and made it a touch's slowest. True when it
// gathered again.
bool keep_neighbourhood(Bvh::Neighbourhood& near, const Bvh& bvh, std::uint32_t face, const glm::dvec3& p,
                        double regather_share) noexcept {
  const glm::dvec3 half_width = 0.5 * (glm::dvec3(near.high) - glm::dvec3(near.low));
  const glm::dvec3 offset = glm::abs(p - 0.5 * (glm::dvec3(near.high) + glm::dvec3(near.low)));
  if (bvh.gathered_here(near) && glm::all(glm::lessThanEqual(offset, regather_share * half_width)))
    return false;
  const float size =
      face != Bvh::no_neighbour ? bvh.triangle(face).longest_edge_mm() : bvh.typical_triangle_size_mm();
  const float half = std::max(float(neighbourhood_faces) * size, float(min_neighbourhood_mm));
  bvh.gather(near, glm::vec3(p) - half, glm::vec3(p) + half);
  return true;
}

// The edge of the face `on` that a point in its plane lies on, within `tolerance`, or -1: off the
// edges, or within it of two (at a corner).
int edge_at(const Bvh& bvh, const Candidate& on, const glm::dvec3& point, double tolerance) noexcept {
  const Bvh::Triangle& tri = bvh.triangle(on.primitive);
  int edge = -1;
  for (int e = 0; e < 3; ++e) {
    const glm::dvec3 a(tri.vertices[std::size_t(e)]), b(tri.vertices[std::size_t((e + 1) % 3)]);
    const glm::dvec3 along = b - a;
    if (std::abs(glm::dot(glm::cross(along, point - a), on.normal)) > tolerance * glm::length(along))
      continue;
    if (edge >= 0) return -1;
    edge = e;
  }
  return edge;
}

// Where a search step starts: the point, the faces it rests on (with their multipliers), whether the
// saddle step was taken, whether it was just handed over an edge, from where and by which face (as
// last set), and the face last met. All that a step does follows from these and the HIP: a step that
// starts where an earlier one of the tick did, to the bit, repeats it, and the search would go round
// that loop to the cap.
struct StepStart {
  glm::dvec3 point;
  std::array<Candidate, max_candidates> faces;
  int face_count;
  bool stepped_over_saddle;
  bool handed_over;
  glm::dvec3 handover_from;
  std::uint32_t handover_face;
  std::uint32_t last_primitive;

  bool operator==(const StepStart& other) const noexcept {
    return point == other.point && face_count == other.face_count &&
           std::equal(faces.begin(), faces.begin() + face_count, other.faces.begin(),
                      [](const Candidate& a, const Candidate& b) {
                        return a.primitive == b.primitive && a.multiplier == b.multiplier;
                      }) &&
           stepped_over_saddle == other.stepped_over_saddle && handed_over == other.handed_over &&
           handover_from == other.handover_from && handover_face == other.handover_face &&
           last_primitive == other.last_primitive;
  }
};

// The steps of a tick remembered to see it come back to one: from its fifth on (most ticks take one to
// three steps, and pay nothing; a loop is seen once it has gone round after that), the last 16 (the
// loops seen take 4 and 6 steps; the default cap is 16).
constexpr int first_remembered_step = 4;
constexpr int remembered_steps = 16;

}  // namespace

void ProxyState::reset(glm::vec3 p) noexcept {
  position_mm = glm::dvec3(p);
  constraint_count = 0;
  placed = true;
  last_iterations = 0;
  last_cut_short = false;
  neighbourhood = {};
}

Contact proxy_step(ProxyState& state, const Bvh& bvh, glm::vec3 hip_mm, const ProxyParams& params,
                   ObjectMask touchable) noexcept {
  Contact contact;
  contact.hip_mm = hip_mm;
  if (!is_finite(hip_mm)) return contact;
  if (!state.placed) state.reset(hip_mm);
  const glm::dvec3 hip(hip_mm);
  const double epsilon = params.surface_epsilon_mm;
  const double tolerance = 1e-3 * epsilon;

  // Warm start from the planes the proxy rested on (sliding on a face then costs one segment), except
  // those whose surface the HIP is now on or in front of (they hold nothing back) and those of objects
  // no longer touchable.
  Candidate c[max_candidates];
  int count = 0;
  for (int i = 0; i < state.constraint_count; ++i) {
    const ProxyConstraint& k = state.constraints[std::size_t(i)];
    if (glm::dot(k.normal, hip) < k.offset_mm - epsilon && bvh.primitive_seen(touchable, k.primitive))
      c[count++] = {k.normal, k.offset_mm, k.primitive, k.multiplier_mm};
  }
  glm::dvec3 p = state.position_mm;
  keep_neighbourhood(state.neighbourhood, bvh, count > 0 ? c[0].primitive : Bvh::no_neighbour, p,
                     regather_in_tick);
  const Bvh::Neighbourhood* near = &state.neighbourhood;
  // The last face met, for the contact when the segment cap cuts a search short.
  std::uint32_t last_primitive = count > 0 ? c[0].primitive : 0;
  bool handed_over = false;       // the last edge crossed handed the proxy to the face beyond
  glm::dvec3 handover_from(0.0);  // ... from this nearest point of the face before
  std::uint32_t handover_face = Bvh::no_neighbour;  // ... and that face (none: it left a wedge)

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

  // At an edge or vertex where the faces meet in a ridge or saddle, a face the proxy touches but does
  // not rest on may come nearer the HIP than where it rests: it moves onto that face's nearest point
  // when the straight way there is free. Each such step brings it nearer the HIP, so the search cannot
  // cycle. False when there is no such face (a local minimum of its distance to the HIP). The faces
  // `known` names are known to be no nearer and are not searched.
  bool stepped_over_saddle = false;
  const auto step_onto_closer_face = [&](std::array<std::uint32_t, 2> known) {
    const BvhHit closer = bvh.closest_point_near(hip, p, near_reach * epsilon, touchable, near, known);
    if (!closer.hit() || double(closer.distance_mm) >= glm::distance(p, hip) - 2.0 * epsilon ||
        std::any_of(c, c + count, [&](const Candidate& k) { return k.primitive == closer.primitive; })) {
      return false;
    }
    const Candidate face = resting_on(bvh, closer.primitive, epsilon);
    const Bvh::Triangle& tri = bvh.triangle(closer.primitive);
    const glm::dvec3 onto =
        closest_point_on_triangle(hip, glm::dvec3(tri.vertices[0]), glm::dvec3(tri.vertices[1]),
                                  glm::dvec3(tri.vertices[2])) +
        face.normal * epsilon;
    // The straight way there runs through the surface (a saddle): rest on that face where the proxy
    // is and walk over it (its walls met on the walk), once a tick so that the search cannot cycle.
    if (bvh.first_hit(p, onto, Faces::front, tolerance, touchable, near).hit()) {
      if (stepped_over_saddle) return false;
      stepped_over_saddle = true;
    } else {
      p = onto;
    }
    c[0] = face;
    count = 1;
    last_primitive = closer.primitive;
    handed_over = false;
    return true;
  };

  // At a vertex with the HIP behind the faces round it: the proxy rests where they come nearest the
  // HIP, when that is among them and there is a free way there: straight, or by the vertex (over it on
  // the planes it will rest on: out of a pocket at the vertex into a valley beyond a ridge). Resting on
  // an edge or a corner, a face of something else it touches may come nearer: it steps onto that face
  // and the search goes on.
  enum class Rest { none, rested, stepped_on };
  const auto rest_round = [&](const glm::dvec3& vertex) {
    Candidate resting[2];
    int resting_count = 0;
    glm::dvec3 rest;
    bool inside_face = false;
    if (!rest_round_vertex(bvh, c[0].primitive, vertex, hip, epsilon, tolerance, resting, resting_count, rest,
                           inside_face))
      return Rest::none;
    const auto free_way = [&](const glm::dvec3& from, const glm::dvec3& to) {
      return from == to || bvh.clear_above(resting[0].primitive, from, to) ||
             !bvh.first_hit(from, to, Faces::front, tolerance, touchable, near).hit();
    };
    if (!free_way(p, rest)) {
      const Solution over = solve(resting, resting_count, vertex, tolerance);
      if (!over.found || !free_way(p, over.point) || !free_way(over.point, rest)) return Rest::none;
    }
    p = rest;
    count = resting_count;
    std::copy(resting, resting + count, c);
    last_primitive = c[0].primitive;
    handed_over = false;
    if (!inside_face &&
        step_onto_closer_face({c[0].primitive, count > 1 ? c[1].primitive : Bvh::no_neighbour}))
      return Rest::stepped_on;
    return Rest::rested;
  };
  // A corner all the planes share, within reach of the proxy: where the faces round a vertex may be
  // taken together (below: at a pocket, or wedged twice there), once a tick.
  const auto shared_corner_in_reach = [&](glm::dvec3& vertex) {
    return shared_corner(bvh, c, count, vertex) && glm::distance(p, vertex) <= near_reach * epsilon;
  };
  bool took_faces_round = false;
  bool wedged_at_vertex = false;  // wedged this tick within reach of a corner its planes share

  // A search can go round a loop: a solve's goal past the end of its triangles, found again from
  // there face by face back to the same planes (6 steps, 2.9 mm deep in a sulcus of the phantom brain),
  // or three faces round a vertex within a micrometre of the tip (4 steps). Coming back to where a step
  // of this tick started, it ends where the cap would have ended it, without the steps between.
  std::array<StepStart, remembered_steps> started;
  bool went_round = false;
  int iteration = 0;
  while (iteration < params.max_iterations) {
    if (iteration >= first_remembered_step) {
      StepStart start{
          p, {}, count, stepped_over_saddle, handed_over, handover_from, handover_face, last_primitive};
      std::copy(c, c + count, start.faces.begin());
      const int step = iteration - first_remembered_step;  // its place among the remembered
      const auto remembered = started.begin() + std::min(step, remembered_steps);
      const auto again = std::find(started.begin(), remembered, start);
      went_round = again != remembered;
      if (went_round) {
        // The steps from the earlier one to this would repeat until the cap: it ends where the cap
        // would have ended it, to the bit, without taking them.
        const int loop_length = 1 + (step - 1 - int(again - started.begin())) % remembered_steps;
        const int loop_start = step - loop_length;
        const int at_cap_step =
            loop_start + (params.max_iterations - first_remembered_step - loop_start) % loop_length;
        const StepStart& at_cap = started[std::size_t(at_cap_step % remembered_steps)];
        p = at_cap.point;
        count = at_cap.face_count;
        std::copy(at_cap.faces.begin(), at_cap.faces.begin() + count, c);
        last_primitive = at_cap.last_primitive;
        break;
      }
      started[std::size_t(step % remembered_steps)] = start;
    }
    ++iteration;
    const int offered = count;
    const Solution s = solve(c, count, hip, tolerance);
    bool at_edge = false, wedged = false;
    glm::dvec3 nearest(0.0);
    if (s.found) {
      int kept = 0;
      for (int i = 0; i < count; ++i) {
        if (s.mask & (1u << i)) {
          c[kept] = c[i];
          c[kept++].multiplier = s.multiplier[i];
        }
      }
      count = kept;
      glm::dvec3 goal = s.point;
      if (offered == 1 && count == 1) {
        // On one face with nothing else in play: walk to the nearest point of the triangle, not of its
        // plane, so the proxy settles on an edge or vertex where that is the surface's nearest point.
        // (When the plane's point is more than a triangle away, it takes the plane's long stride
        // instead and finds its footing again there: a far jump of the tip is not walked a triangle at
        // a time.)
        const Bvh::Triangle& tri = bvh.triangle(c[0].primitive);
        const glm::dvec3 v0(tri.vertices[0]), v1(tri.vertices[1]), v2(tri.vertices[2]);
        nearest = closest_point_on_triangle(hip, v0, v1, v2);
        const glm::dvec3 lifted = nearest + (c[0].offset - glm::dot(c[0].normal, nearest)) * c[0].normal;
        const double beyond2 = glm::dot(lifted - goal, lifted - goal);
        const double size2 =
            std::max({glm::dot(v1 - v0, v1 - v0), glm::dot(v2 - v1, v2 - v1), glm::dot(v0 - v2, v0 - v2)});
        if (beyond2 <= size2) {
          at_edge = beyond2 > tolerance * tolerance;
          goal = lifted;
          // Handed back to the edge or vertex it was handed over from: the surface's nearest point,
          // unless a face it touches comes nearer. Not this face nor the one before: their nearest
          // points are where the proxy was handed over, no nearer than its own distance less epsilon.
          if (at_edge && handed_over && glm::distance(nearest, handover_from) < tolerance) {
            if (step_onto_closer_face({c[0].primitive, handover_face})) continue;
            break;
          }
        }
      }
      const glm::dvec3 path = goal - p;
      if (glm::dot(path, path) > 1e-24) {  // 1e-12 mm
        // Above its own face, in the space no other triangle enters (the walks of a slide), nothing
        // can be in the way: no cast.
        const BvhHit hit = count > 0 && bvh.clear_above(c[0].primitive, p, goal)
                               ? BvhHit{}
                               : bvh.first_hit(p, goal, Faces::front, tolerance, touchable, near);
        if (hit.hit()) {
          c[count++] = stop_before(hit, goal);
          handed_over = false;
          continue;
        }
        p = goal;
      }
      if (!at_edge) {
        if (count == 0) break;  // free at the HIP
        if (!supported(bvh, c, count, p, epsilon)) {
          // Within reach of a corner the planes share, the proxy sits in a pocket at that vertex: the
          // faces round it are taken together, as at a walk's vertex. Dropping the planes found the
          // same ones again from where it stood and went round until the cap: 8 steps a tick, 51 ticks
          // of one press-slide deep in a sulcus of the phantom brain (docs/design.md, "eleventh step").
          // Once a tick: from the same place it comes out the same.
          glm::dvec3 vertex;
          if (!took_faces_round && count >= 2 && shared_corner_in_reach(vertex)) {
            took_faces_round = true;
            const Rest rest = rest_round(vertex);
            if (rest == Rest::stepped_on) continue;
            if (rest == Rest::rested) break;
          }
          // Followed its planes past the end of their triangles: find the constraints again from here.
          count = 0;
          handed_over = false;
          continue;
        }
        if (count == 1) break;  // resting on a face
        // Wedged where two or three planes meet. A true crease or corner: the way toward the HIP runs
        // into one of its own faces. Where the faces only meet at a ridge or saddle vertex, another face
        // of the surface is in view, and the proxy goes on over it (as planes, they would hold it
        // there however far the tip went).
        // Wedged a second time this tick within reach of a corner its planes share, the search has gone
        // round the faces of a vertex (a look meets the next face round a micrometre away and takes the
        // proxy over, and two planes wedge it again) and would go on round until the loop check ended
        // it: 8 or 9 steps where a press of the phantom brain first touches at a vertex (docs/design.md,
        // "twelfth step"; the second wedge was at the first one's vertex in every tick measured). The
        // faces round it are taken together, as at a walk's vertex; with no free way to where they come
        // nearest, the proxy stays, as close as it gets.
        glm::dvec3 vertex;
        if (!took_faces_round && shared_corner_in_reach(vertex)) {
          if (wedged_at_vertex) {
            took_faces_round = true;
            const Rest rest = rest_round(vertex);
            if (rest == Rest::stepped_on) continue;
            break;
          }
          wedged_at_vertex = true;
        }
        wedged = true;
      }
    }
    // At an edge of its face, not a vertex: the face across it takes over, as a look toward the HIP
    // would find it, without the cast (one a crossed edge: on fine meshes a third of a sliding tick).
    // Its walk, cast like any other, meets whatever else is in the way, or reaches the HIP when the
    // HIP is in front of its plane.
    const int edge = at_edge ? edge_at(bvh, c[0], nearest, tolerance) : -1;
    if (edge >= 0) {
      const std::uint32_t beyond = bvh.neighbour(c[0].primitive, edge);
      if (beyond != Bvh::no_neighbour) {
        handover_face = c[0].primitive;
        c[0] = resting_on(bvh, beyond, epsilon);
        count = 1;
        last_primitive = beyond;
        handed_over = true;
        handover_from = nearest;
        continue;
      }
    }
    // At a vertex of its face, at an edge the mesh gives no face across, or wedged where no goal fits:
    // look from here toward the HIP. From a vertex, among the faces around it first (the one the look
    // meets unless another surface passes within micrometres); the whole look when none is in the way.
    BvhHit next;
    if (at_edge && edge < 0) {
      next = bvh.first_hit_around(p, hip, c[0].primitive, nearest, tolerance, touchable);
      // The HIP behind the faces there: the proxy rests where they come nearest it, if it can.
      const Rest rest = next.hit() ? rest_round(nearest) : Rest::none;
      if (rest == Rest::stepped_on) continue;
      if (rest == Rest::rested) break;
    }
    if (!next.hit()) next = bvh.first_hit(p, hip, Faces::front, tolerance, touchable, near);
    if (!next.hit()) {  // nothing in the way: the HIP is outside and reachable
      p = hip;
      count = 0;
      break;
    }
    if (!s.found) break;
    if (std::any_of(c, c + count, [&](const Candidate& k) { return k.primitive == next.primitive; })) {
      // Its own face in the way: as close as it gets, unless a face it touches comes nearer.
      if (step_onto_closer_face({Bvh::no_neighbour, Bvh::no_neighbour})) continue;
      break;
    } else {
      // Past its edge, or out of a false corner: the face in view takes over (a concave one is met
      // again as a wall on the walk).
      handover_face = wedged ? Bvh::no_neighbour : c[0].primitive;
      c[0] = stop_before(next, hip);
    }
    count = 1;
    handed_over = true;
    handover_from = wedged ? p : nearest;
  }

  state.position_mm = p;
  state.last_iterations = iteration;
  state.last_cut_short = went_round || iteration >= params.max_iterations;
  // Keep at most three planes (the solve keeps no more; a capped tick may end with a fourth).
  const int first = std::max(0, count - 3);
  state.constraint_count = count - first;
  for (int i = first; i < count; ++i) {
    state.constraints[std::size_t(i - first)] = {c[i].normal, c[i].offset, c[i].multiplier, c[i].primitive};
  }

  contact.point_mm = glm::vec3(p);
  const glm::dvec3 spring = p - hip;
  const double depth = glm::length(spring);
  // In contact while a plane holds the proxy back, or while a search the cap cut short left it apart
  // from the HIP (it resumes next tick).
  if (state.constraint_count == 0 && depth <= epsilon) return contact;
  std::uint32_t primary = last_primitive;
  double strongest = -1.0;
  for (int i = 0; i < state.constraint_count; ++i) {
    if (state.constraints[std::size_t(i)].multiplier_mm > strongest) {
      strongest = state.constraints[std::size_t(i)].multiplier_mm;
      primary = state.constraints[std::size_t(i)].primitive;
    }
  }
  const Bvh::Location location = bvh.locate(primary);
  contact.object = location.object;
  contact.triangle = location.triangle;
  if (depth > 0.5 * epsilon) {
    contact.normal = glm::vec3(spring / depth);
  } else {
    const Bvh::Triangle& tri = bvh.triangle(primary);
    contact.normal =
        glm::vec3(glm::normalize(glm::cross(glm::dvec3(tri.vertices[1]) - glm::dvec3(tri.vertices[0]),
                                            glm::dvec3(tri.vertices[2]) - glm::dvec3(tri.vertices[0]))));
  }
  contact.depth_mm = float(depth);
  return contact;
}

void proxy_prepare(ProxyState& state, const Bvh& bvh) noexcept {
  if (!state.placed) return;
  const std::uint32_t face = state.constraint_count > 0 ? state.constraints[0].primitive : Bvh::no_neighbour;
  if (keep_neighbourhood(state.neighbourhood, bvh, face, state.position_mm, regather_between_ticks))
    bvh.prefetch(state.neighbourhood);
}

}  // namespace palpate
