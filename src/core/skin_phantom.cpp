// The skin phantom: a height field over directions from a point inside the head, r(w) (so the surface is
// star-shaped and cannot cross itself): the smooth maximum of the distances to a few solids that contain
// that point (cranium, face, jaw, neck), plus smooth relief for the features of a face. A base sphere's
// vertices are put on it, then smoothed and flipped into even triangles.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

#include "core/phantom_math.hpp"
#include "core/radial_relaxation.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate {
namespace {

using detail::smooth_max;
using detail::smooth_min;
using detail::smoothstep;

constexpr double pi = std::numbers::pi;
constexpr double far_mm = 1e6;  // "no surface this way"

// The centre of the height field, inside every solid below: low and back enough that no ray from it runs
// along the neck or the underside of the chin, high enough that it sees the underside of the nose.
constexpr glm::dvec3 skin_centre(skin_phantom_star_centre);

// Distance along unit direction w from skin_centre (inside) to the ellipsoid's surface.
double ellipsoid_exit(glm::dvec3 centre, glm::dvec3 half_axes, glm::dvec3 w) {
  const glm::dvec3 d = (skin_centre - centre) / half_axes, e = w / half_axes;
  const double a = glm::dot(e, e), b = 2.0 * glm::dot(d, e), c = glm::dot(d, d) - 1.0;
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

// The same for the "4-norm ellipsoid" x^4 + y^4 + z^4 = 1 (in half-axis units): a block with round
// edges, for the flat front of the face. Newton's method on the convex f(t) = |p(t)|_4^4 - 1 from the
// circumscribed box's exit, where f >= 0, steps down to the root without overshooting it; the inscribed
// ellipsoid's exit bounds it from below.
double block_exit(glm::dvec3 centre, glm::dvec3 half_axes, glm::dvec3 w) {
  const glm::dvec3 d = (skin_centre - centre) / half_axes, e = w / half_axes;
  double t = far_mm;
  for (int i = 0; i < 3; ++i) {
    if (e[i] != 0.0) t = std::min(t, (std::copysign(1.0, e[i]) - d[i]) / e[i]);
  }
  const double lowest = ellipsoid_exit(centre, half_axes, w);
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 p = d + t * e, p2 = p * p;
    t -= (glm::dot(p2, p2) - 1.0) / (4.0 * glm::dot(p2 * p, e));
  }
  return std::max(t, lowest);
}

// The cranium: an egg, taller below its equator so it covers the temporal lobes.
double cranium_exit(glm::dvec3 w) {
  const glm::dvec3 centre(0.0, -3.0, -6.0);
  const double upper = ellipsoid_exit(centre, {82.0, 98.0, 78.0}, w);
  if (skin_centre.z + upper * w.z >= centre.z) return upper;
  return ellipsoid_exit(centre, {82.0, 98.0, 90.0}, w);
}

// The neck stub: a cone widening downward toward the shoulders, with a rounded flat end.
double neck_exit(glm::dvec3 w) {
  const glm::dvec3 apex(0.0, -22.0, 120.0);
  const double slope = 0.2;  // radius growth per mm down
  const double bottom = -210.0, top = -30.0;
  const glm::dvec3 d = skin_centre - apex;
  const double a = w.x * w.x + w.y * w.y - slope * slope * w.z * w.z;
  const double b = 2.0 * (d.x * w.x + d.y * w.y - slope * slope * d.z * w.z);
  const double c = d.x * d.x + d.y * d.y - slope * slope * d.z * d.z;  // < 0: the centre is inside
  double side = far_mm;
  if (a > 0.0) {
    const double root = std::sqrt(b * b - 4.0 * a * c);
    side =
        b > 0.0 ? 2.0 * c / (-b - root) : (-b + root) / (2.0 * a);  // the positive root, without cancellation
  }
  const double floor = w.z < 0.0 ? (bottom - skin_centre.z) / w.z : far_mm;
  const double ceiling = w.z > 0.0 ? (top - skin_centre.z) / w.z : far_mm;
  return std::min(smooth_min(side, floor, 30.0), ceiling);
}

double bump(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 width) {
  const glm::dvec3 d = (p - centre) / width;
  return detail::bell(glm::dot(d, d));
}

// Features of the face (mm outward) as functions of where the plain head's surface is.
double face_relief(glm::dvec3 p) {
  const double cheeks = 4.0 * (bump(p, {50.0, 70.0, -60.0}, {16.0, 25.0, 16.0}) +
                               bump(p, {-50.0, 70.0, -60.0}, {16.0, 25.0, 16.0}));
  const double front = smoothstep(50.0, 80.0, p.y);
  if (front <= 0.0) return cheeks;
  // The nose: a ridge from the root between the eyes down to the tip, widening toward the nostrils.
  const double nose_height = 20.0 * smoothstep(-24.0, -64.0, p.z) * (1.0 - smoothstep(-66.0, -78.0, p.z));
  const double nose_width = 6.0 + 7.0 * smoothstep(-30.0, -70.0, p.z);
  const double nose = nose_height * detail::bell((p.x / nose_width) * (p.x / nose_width));
  const double brow = 5.0 * bump(p, {0.0, 92.0, -24.0}, {45.0, 30.0, 10.0});
  const double eyes = -7.0 * (bump(p, {33.0, 92.0, -40.0}, {13.0, 30.0, 10.0}) +
                              bump(p, {-33.0, 92.0, -40.0}, {13.0, 30.0, 10.0}));
  const double lips = 5.0 * bump(p, {0.0, 96.0, -98.0}, {22.0, 30.0, 9.0});
  const double chin = 10.0 * bump(p, {0.0, 85.0, -145.0}, {20.0, 30.0, 14.0});
  return front * (nose + brow + eyes + lips + chin) + cheeks;
}

// Distance (mm) from skin_centre to the skin in unit direction w.
double skin_radius(glm::dvec3 w) {
  const double face = block_exit({0.0, 40.0, -78.0}, {64.0, 58.0, 52.0}, w);
  const double jaw = ellipsoid_exit({0.0, 22.0, -100.0}, {52.0, 70.0, 66.0}, w);
  const double head = smooth_max(cranium_exit(w), smooth_max(face, jaw, 12.0), 20.0);
  const double plain = smooth_max(head, neck_exit(w), 18.0);
  return plain + face_relief(skin_centre + plain * w);
}

}  // namespace

Mesh make_skin_phantom(std::size_t vertices) {
  detail::require_phantom_vertices("make_skin_phantom", vertices);
  Mesh mesh = make_sphere(1.0f, vertices);
  for (glm::vec3& p : mesh.positions_mm) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(p));
    p = glm::vec3(skin_centre + skin_radius(w) * w);
  }
  detail::relax_radial_mesh(mesh, skin_centre, skin_radius, 2, 25.0 * pi / 180.0);
  compute_vertex_normals(mesh);
  return mesh;
}

}  // namespace palpate
