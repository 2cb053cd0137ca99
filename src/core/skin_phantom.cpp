// The skin phantom: a radial surface about a point inside the head (so it is star-shaped and cannot cross
// itself), built from a few convex solids that contain that point (cranium, face, neck), blended by a
// smooth maximum of their radial distances, plus smooth bumps for the features of a face.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

#include "core/edge_flips.hpp"
#include "core/phantom_math.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate {
namespace {

using detail::smooth_max;
using detail::smooth_min;
using detail::smoothstep;

constexpr double pi = std::numbers::pi;
constexpr double far_mm = 1e6;  // "does not end in this direction"

// The centre of the radial surface: behind the nose, above the chin, inside every solid below.
constexpr glm::dvec3 skin_centre{0.0, 0.0, -40.0};

// Distance along unit direction w from skin_centre (inside) to the ellipsoid's surface.
double ellipsoid_exit(glm::dvec3 centre, glm::dvec3 half_axes, glm::dvec3 w) {
  const glm::dvec3 d = (skin_centre - centre) / half_axes, e = w / half_axes;
  const double a = glm::dot(e, e), b = 2.0 * glm::dot(d, e), c = glm::dot(d, d) - 1.0;
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

// The cranium: taller below its centre so it covers the temporal lobes.
double cranium_exit(glm::dvec3 w) {
  const glm::dvec3 centre(0.0, -3.0, -8.0);
  const double below = w.z < 0.0 ? 92.0 : 80.0;
  return ellipsoid_exit(centre, {79.0, 95.0, below}, w);
}

double face_exit(glm::dvec3 w) { return ellipsoid_exit({0.0, 30.0, -70.0}, {64.0, 66.0, 92.0}, w); }

// The neck stub: a cone widening downward (toward the shoulders), cut by a rounded flat end.
double neck_exit(glm::dvec3 w) {
  const glm::dvec3 apex(0.0, -18.0, 100.0);
  const double slope = 0.23;  // radius growth per mm down
  const double bottom = -205.0, top = -30.0;
  const glm::dvec3 d = skin_centre - apex;
  const double a = w.x * w.x + w.y * w.y - slope * slope * w.z * w.z;
  const double b = 2.0 * (d.x * w.x + d.y * w.y - slope * slope * d.z * w.z);
  const double c = d.x * d.x + d.y * d.y - slope * slope * d.z * d.z;  // < 0: the centre is inside
  double side = far_mm;
  if (a > 0.0) {
    const double root = std::sqrt(b * b - 4.0 * a * c);
    side = b > 0.0 ? 2.0 * c / (-b - root) : (-b + root) / (2.0 * a);  // the positive root, without cancellation
  }
  const double floor = w.z < 0.0 ? (bottom - skin_centre.z) / w.z : far_mm;
  const double ceiling = w.z > 0.0 ? (top - skin_centre.z) / w.z : far_mm;
  return std::min(smooth_min(side, floor, 30.0), ceiling);
}

double gaussian(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 width) {
  const glm::dvec3 d = (p - centre) / width;
  return std::exp(-glm::dot(d, d));
}

// Features of the face, in mm outward, as functions of where the plain head's surface is.
double face_relief(glm::dvec3 p) {
  const double front = smoothstep(55.0, 85.0, p.y);
  // The nose: a ridge from the root between the eyes to the tip, widening toward the nostrils.
  const double nose_height = 19.0 * smoothstep(-22.0, -62.0, p.z) * (1.0 - smoothstep(-64.0, -76.0, p.z));
  const double nose_width = 6.0 + 6.0 * smoothstep(-30.0, -68.0, p.z);
  const double nose = nose_height * std::exp(-(p.x / nose_width) * (p.x / nose_width));
  const double brow = 4.0 * gaussian(p, {0.0, 90.0, -18.0}, {42.0, 30.0, 9.0});
  const double eyes = -6.0 * (gaussian(p, {33.0, 88.0, -38.0}, {13.0, 30.0, 10.0}) +
                              gaussian(p, {-33.0, 88.0, -38.0}, {13.0, 30.0, 10.0}));
  const double cheeks = 4.0 * (gaussian(p, {52.0, 62.0, -58.0}, {18.0, 25.0, 16.0}) +
                               gaussian(p, {-52.0, 62.0, -58.0}, {18.0, 25.0, 16.0}));
  const double lips = 4.0 * gaussian(p, {0.0, 95.0, -97.0}, {22.0, 30.0, 9.0});
  const double chin = 9.0 * gaussian(p, {0.0, 85.0, -142.0}, {22.0, 30.0, 16.0});
  return front * (nose + brow + eyes + lips + chin) + cheeks;
}

double skin_radius(glm::dvec3 w) {
  const double head = smooth_max(cranium_exit(w), face_exit(w), 14.0);
  const double plain = smooth_max(head, neck_exit(w), 16.0);
  return plain + face_relief(skin_centre + plain * w);
}

}  // namespace

Mesh make_skin_phantom(std::size_t vertices) {
  constexpr std::size_t min_vertices = 500;
  if (vertices < min_vertices) {
    throw Error("make_skin_phantom: need at least " + std::to_string(min_vertices) + " vertices, got " +
                std::to_string(vertices));
  }
  Mesh mesh = make_sphere(1.0f, vertices);
  for (glm::vec3& p : mesh.positions) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(p));
    p = glm::vec3(skin_centre + skin_radius(w) * w);
  }
  detail::flip_toward_delaunay(mesh, skin_centre, 25.0 * pi / 180.0);
  compute_vertex_normals(mesh);
  return mesh;
}

}  // namespace palpate
