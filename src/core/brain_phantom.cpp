// The brain phantom: a height field over directions from the origin, r(w) (so the surface is star-shaped
// and cannot cross itself), sampled where its folds need vertices.
//
// Shape: a smooth hull (egg-shaped ellipsoid, flattened base, temporal lobes lower at the sides), less the
// depth of the sulci, which follow the zero lines of a random spherical wave, and of the longitudinal
// fissure along the midline. Each groove is a narrow slot (round bottom, steep walls, round lips).
//
// Sampling: the vertices of a base sphere move across each groove toward its centre line so that they
// spread along the groove's cross-section instead of leaving its steep walls to a few stretched
// triangles; where a move would turn a triangle over it is backed off (the shape is the same, only the
// sampling changes). A few rounds of smoothing and edge flips then even the triangles out.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "core/phantom_math.hpp"
#include "core/radial_relaxation.hpp"
#include "core/slot_profile.hpp"
#include "core/spherical_wave.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate {
namespace {

using detail::smoothstep;
constexpr double pi = std::numbers::pi;
constexpr double degrees = pi / 180.0;

// Distance (mm) from the centre to the hull in unit direction u (x right, y front, z up).
double hull_radius(glm::dvec3 u) {
  // Egg-shaped from above: narrower frontal lobes, widest behind the middle.
  const double half_width = 70.5 - 6.0 * smoothstep(-0.1, 0.9, u.y);
  const double half_length = 82.5;
  const double half_height = u.z > 0.0 ? 58.0 : 72.0;  // the bottom is cut by the base below
  const double inv_ellipsoid =
      std::sqrt(u.x * u.x / (half_width * half_width) + u.y * u.y / (half_length * half_length) +
                u.z * u.z / (half_height * half_height));
  // The base: a floor whose depth below the centre varies, lowest under the temporal lobes (at the sides,
  // a little in front of the middle), highest under the frontal lobes.
  const double side = std::abs(u.x) - 0.62, front = u.y - 0.12;
  const double temporal = detail::bell((side * side + front * front) / 0.05);
  const double floor_depth = 53.0 + 11.0 * temporal - 13.0 * smoothstep(0.25, 0.75, u.y);
  const double inv_floor = std::max(0.0, -u.z) / floor_depth;
  // The nearer of the two surfaces, with a rounded edge: an 8-norm of the inverse distances.
  const double a2 = inv_ellipsoid * inv_ellipsoid, b2 = inv_floor * inv_floor;
  const double a8 = a2 * a2 * a2 * a2, b8 = b2 * b2 * b2 * b2;
  return 1.0 / std::sqrt(std::sqrt(std::sqrt(a8 + b8)));
}

// How much of the fissure there is along the midline: from below the frontal pole, over the top, to below
// the occipital pole; none across the base.
double fissure_presence(glm::dvec3 u) {
  // The height of the direction's projection on the midline plane: it ends where that dips 35 to 57
  // degrees below the horizontal.
  const double off_axis = std::sqrt(u.y * u.y + u.z * u.z);
  if (off_axis <= 0.0) return 0.0;
  return 1.0 - smoothstep(0.57, 0.84, -u.z / off_axis);
}

// Signed distance (mm, like x) from the midline, measured on the hull.
double midline_distance(glm::dvec3 u, double hull) {
  return hull * std::asin(std::clamp(u.x, -1.0, 1.0));
}

// Rotates unit direction u by `angle` (rad) toward unit tangent t.
glm::dvec3 move_on_sphere(glm::dvec3 u, glm::dvec3 t, double angle) {
  return glm::normalize(std::cos(angle) * u + std::sin(angle) * t);
}

struct FissureDesign {
  double depth_mm = 25.0;  // below the hemisphere tops
  // Bottom radius 1.5 mm, lip radius 3 mm, walls at 87 degrees, in the rim's scale: the walls converge
  // with depth (a radial surface).
  detail::SlotShape shape{1.5, 3.0, 87.0 * degrees};
};

struct SulcusDesign {
  int wave_degree = 15;  // crest to crest about pi R / sqrt(l (l + 1)): 12 to 17 mm
  std::uint64_t seed = 0x70616c70617465ull;
  double depth_mm = 13.0;  // 10 to 13 mm, deeper where the wave is strong
  // Bottom radius 1 mm, lip radius 1.2 mm, walls at 85 degrees, in phase units: a little wider on the
  // surface, where the wave's phase changes slower than the nominal wavenumber says (see read()).
  detail::SlotShape shape{1.0, 1.2, 85.0 * degrees};
  double midline_free_mm = 11.0;  // no sulci this close to the midline where the fissure is...
  double fade_in_mm = 6.0;        // ...then they deepen over this distance
  // Where the wave and its slope are both small its phase turns fast around a point, which would make
  // features finer than the mesh; this floor on the phase's cosine (a fraction of the typical amplitude)
  // smooths them into plain junctions of sulci.
  double phase_floor = 0.4;
};

class BrainShape {
 public:
  explicit BrainShape(double vertex_spacing_mm)
      : wave_(sulci_.wave_degree, sulci_.seed),
        typical_amplitude_(std::sqrt(2.0) * wave_.rms()),
        // Grooves a few vertices across need vertices about a millimetre apart: coarser meshes get
        // shallower grooves. Sulci deepen from about 10,000 to 30,000 vertices, the fissure from
        // about 2,700 to 11,000.
        sulcus_scale_(smoothstep(2.6, 1.5, vertex_spacing_mm)),
        fissure_scale_(smoothstep(5.0, 2.5, vertex_spacing_mm)) {}

  // The shape: distance (mm) from the centre to the surface in unit direction w.
  double radius(glm::dvec3 w) const {
    const double hull = hull_radius(w);
    const double midline_mm = midline_distance(w, hull);
    const double presence = fissure_presence(w);
    double depth = fissure_profile(presence).depth_at(midline_mm);
    if (const double scale = sulcus_scale(midline_mm, presence); scale > 0.0) {
      const Reading reading = read(wave_(w));
      const double half_period = this->half_period(hull);
      depth +=
          sulcus_profile(scale * reading.depth_fraction, half_period).depth_at(reading.distance(half_period));
    }
    return hull - depth;
  }

  // Sampling: where a base sphere vertex in unit direction u goes across the fissure: keeping its angle
  // around the x axis, so that whole latitude rings of the base sphere (poles on the x axis) move
  // together. The fissure's walls take their rings from the whole hemisphere, from the midline to the
  // pole, so that every ring moves a little rather than a few a lot.
  glm::dvec3 across_fissure(glm::dvec3 u) const {
    const double presence = fissure_presence(u);
    const double off_axis = std::sqrt(u.y * u.y + u.z * u.z);
    if (fissure_scale_ * presence <= 0.0 || off_axis <= 0.0) return u;  // the poles stay
    const double hull = hull_radius(u);
    const double midline_mm = midline_distance(u, hull);
    const detail::SlotProfile::Place place =
        fissure_profile(presence).place(std::abs(midline_mm), hull * pi / 2.0);
    const double angle = std::copysign(place.lateral, midline_mm) / hull;
    return std::sin(angle) * glm::dvec3(1.0, 0.0, 0.0) +
           std::cos(angle) / off_axis * glm::dvec3(0.0, u.y, u.z);
  }

  // Sampling: where a direction u goes across the sulcus it lies beside. Reading the wave as a plane
  // wave of the nominal wavelength, the phase gives the distance from the centre line; the sulcus profile
  // says where that share of its cross-section lies. The move is away from the centre line (up the
  // wave's slope where the wave is positive) or toward it.
  glm::dvec3 across_sulcus(glm::dvec3 u) const {
    const double hull = hull_radius(u);
    const double scale = sulcus_scale(midline_distance(u, hull), fissure_presence(u));
    if (scale <= 0.0) return u;
    const detail::SphericalWave::Sample wave = wave_(u);
    const double gradient_norm = glm::length(wave.gradient);
    if (gradient_norm <= 0.0) return u;  // a crest point: it stays
    const Reading reading = read(wave);
    const double half_period = this->half_period(hull);
    const double distance = reading.distance(half_period);
    const detail::SlotProfile::Place place =
        sulcus_profile(scale * reading.depth_fraction, half_period).place(distance, half_period);
    const glm::dvec3 away = std::copysign(1.0, wave.value) * wave.gradient / gradient_norm;
    return move_on_sphere(u, away, (place.lateral - distance) / hull);
  }

 private:
  struct Reading {
    double phase;           // 0 on a sulcus' centre line, +-pi/2 on the crests between sulci
    double depth_fraction;  // of the full sulcus depth
    double distance(double half_period) const { return std::abs(phase) / (pi / 2.0) * half_period; }  // mm
  };

  // Reads the wave locally as amplitude * sin(phase); slope = |gradient| / wavenumber plays the cosine.
  Reading read(const detail::SphericalWave::Sample& wave) const {
    const double slope = glm::length(wave.gradient) / wave_.wavenumber();
    const double floor = sulci_.phase_floor * typical_amplitude_;
    const double strength = std::sqrt(wave.value * wave.value + slope * slope) / typical_amplitude_;
    return {std::atan2(wave.value, std::sqrt(slope * slope + floor * floor)),
            0.75 + 0.25 * std::min(1.0, strength)};
  }

  double half_period(double hull) const {
    return pi / 2.0 / wave_.wavenumber() * hull;
  }  // mm, centre line to crest

  // Sulci fade out near the fissure, and at low resolution.
  double sulcus_scale(double midline_mm, double presence) const {
    const double near_fissure =
        presence * (1.0 - smoothstep(sulci_.midline_free_mm, sulci_.midline_free_mm + sulci_.fade_in_mm,
                                     std::abs(midline_mm)));
    return sulcus_scale_ * (1.0 - near_fissure);
  }

  // A sulcus `depth_fraction` of the full depth deep, narrowed if needed to leave a crest between sulci.
  detail::SlotProfile sulcus_profile(double depth_fraction, double half_period) const {
    const double depth = sulci_.depth_mm * depth_fraction;
    const detail::SlotProfile profile(depth, sulci_.shape);
    const double room = 0.6 * half_period / profile.half_width();
    if (room >= 1.0) return profile;
    return {depth * room, sulci_.shape, room};
  }

  // The fissure fades out by getting shallower, keeping its width.
  detail::SlotProfile fissure_profile(double presence) const {
    return {fissure_.depth_mm * fissure_scale_ * presence, fissure_.shape};
  }

  SulcusDesign sulci_;
  FissureDesign fissure_;
  detail::SphericalWave wave_;
  double typical_amplitude_;
  double sulcus_scale_;
  double fissure_scale_;
};

// True when triangle (a, b, c) turns counter-clockwise seen from the origin, by a margin relative to its
// size: every triangle doing so makes the mesh star-shaped about the origin.
bool faces_away(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const double volume = glm::dot(a, glm::cross(b, c));
  return volume > 0.0 && volume * volume > 1e-18 * glm::dot(a, a) * glm::dot(b, b) * glm::dot(c, c);
}

// Puts vertex v on the surface in direction from[v] + share * (to[v] - from[v]), then backs the share off
// (halving it a few times, then dropping it) at the vertices of any triangle turned over, until none is.
// `from` must give a valid mesh by itself, so this ends.
void place_on_surface(Mesh& mesh, const BrainShape& shape, const std::vector<glm::dvec3>& from,
                      const std::vector<glm::dvec3>& to, double share) {
  const std::size_t vertices = from.size(), triangles = mesh.triangle_count();
  // The triangles around each vertex, in compressed rows.
  std::vector<std::uint32_t> start(vertices + 1, 0), around(mesh.indices.size());
  for (std::uint32_t v : mesh.indices) ++start[v + 1];
  for (std::size_t i = 1; i <= vertices; ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t c = 0; c < mesh.indices.size(); ++c) around[fill[mesh.indices[c]]++] = c / 3;

  std::vector<double> shares(vertices, share);
  const auto put = [&](std::uint32_t v) {
    const glm::dvec3 w = glm::normalize(from[v] + shares[v] * (to[v] - from[v]));
    mesh.positions_mm[v] = glm::vec3(shape.radius(w) * w);
  };
  const auto turned_over = [&](std::uint32_t t) {
    return !faces_away(mesh.positions_mm[mesh.indices[3 * t]], mesh.positions_mm[mesh.indices[3 * t + 1]],
                       mesh.positions_mm[mesh.indices[3 * t + 2]]);
  };
  for (std::uint32_t v = 0; v < vertices; ++v) put(v);
  std::vector<std::uint32_t> check(triangles), redo;
  for (std::uint32_t t = 0; t < triangles; ++t) check[t] = t;
  for (int round = 0; !check.empty(); ++round) {
    redo.clear();
    for (std::uint32_t t : check) {
      if (!turned_over(t)) continue;
      for (int k = 0; k < 3; ++k) {
        if (shares[mesh.indices[3 * t + k]] > 0.0) redo.push_back(mesh.indices[3 * t + k]);
      }
    }
    std::sort(redo.begin(), redo.end());
    redo.erase(std::unique(redo.begin(), redo.end()), redo.end());
    check.clear();
    for (std::uint32_t v : redo) {
      shares[v] = round < 4 ? 0.5 * shares[v] : 0.0;
      put(v);
      check.insert(check.end(), around.begin() + start[v], around.begin() + start[v + 1]);
    }
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
  }
}

}  // namespace

Mesh make_brain_phantom(std::size_t vertices) {
  detail::require_phantom_vertices("make_brain_phantom", vertices);
  Mesh mesh = make_sphere(1.0f, vertices);
  // Mean edge length on the hull (about 68 mm in radius) of a near-equilateral mesh with this many vertices.
  const double spacing = 68.0 * std::sqrt(8.0 * pi / (std::sqrt(3.0) * double(vertices)));
  const BrainShape shape(spacing);
  std::vector<glm::dvec3> ringed(vertices), folded(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    // The base sphere turned to put its poles on the x axis (x <- z, y <- x, z <- y: a rotation).
    const glm::vec3 p = mesh.positions_mm[v];
    ringed[v] = shape.across_fissure(glm::normalize(glm::dvec3(p.z, p.x, p.y)));
    folded[v] = shape.across_sulcus(ringed[v]);
  }
  // Most of the way across the sulci: the full move turns more triangles over where the wave is not
  // locally a plane wave, and smoothing does the rest.
  place_on_surface(mesh, shape, ringed, folded, 0.7);
  detail::relax_radial_mesh(
      mesh, glm::dvec3(brain_phantom_star_centre), [&shape](glm::dvec3 w) { return shape.radius(w); }, 4,
      25.0 * degrees);
  compute_vertex_normals(mesh);
  return mesh;
}

}  // namespace palpate
