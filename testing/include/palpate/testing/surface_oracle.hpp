#pragma once
// Where a point is with respect to closed surfaces, computed without palpate's BVH or proxy: the judge
// of the haptic tests and of `palpate bench haptics`. Plain grids and brute force, tens of
// microseconds a query; built for checking, and written so that it is easy to trust.
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <vector>

#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::testing {

class SurfaceOracle {
 public:
  virtual ~SurfaceOracle() = default;
  // Signed distance below the surface, positive inside, exact up to depth_limit_mm().
  virtual double depth_mm(glm::vec3 p) const = 0;
  virtual double depth_limit_mm() const { return std::numeric_limits<double>::infinity(); }
  // The outward unit normal of the surface at the surface point nearest `near_surface`.
  virtual glm::dvec3 outward_normal(glm::dvec3 near_surface) const = 0;
  // The distance from `p` to the nearest point of the part of the surface within `reach_mm` of the
  // surface point `around`: how close to p a proxy resting at `around` could get by sliding a little.
  virtual double distance_near(glm::dvec3 p, glm::dvec3 around, double reach_mm) const = 0;
};

// The touchable objects of a scene, each a closed surface, in world space.
class MeshOracle final : public SurfaceOracle {
 public:
  // Allocates. Depths are capped at `depth_cap_mm` (what lies deeper reads as that deep).
  explicit MeshOracle(const Scene& scene, double depth_cap_mm = 8.0);

  // Winding number of all the surfaces around p: signed crossings of rays along +x, +y and +z, each
  // through a grid of the triangles' projections and nudged by ~1e-9 mm in an irrational direction
  // off any projected edge; the majority of the three.
  int winding(const glm::dvec3& p) const;
  bool inside(const glm::dvec3& p) const { return winding(p) > 0; }

  // For the objects containing p, the largest distance to that object's surface; outside all, minus
  // the distance to the nearest surface. Capped.
  double depth_mm(glm::vec3 p) const override;
  double depth_limit_mm() const override { return cap_; }

  struct Nearest {
    bool found = false;
    glm::dvec3 point{0.0};   // on the surface, world mm
    glm::dvec3 normal{0.0};  // the mesh's vertex normals interpolated there (its face normal without)
    double distance_mm = 0.0;
  };
  // The surface point nearest p within `max_distance_mm` (any object), or not found.
  Nearest nearest(const glm::dvec3& p, double max_distance_mm) const;
  // The same among the triangles that stay farther than `radius_mm` from `from`: how near p comes to
  // another part of the surface than the one around `from`.
  Nearest nearest_away(const glm::dvec3& p, double max_distance_mm, const glm::dvec3& from,
                       double radius_mm) const;

  glm::dvec3 outward_normal(glm::dvec3 near_surface) const override;
  double distance_near(glm::dvec3 p, glm::dvec3 around, double reach_mm) const override;

  // Whether the segment meets any triangle (either side, boundary included): brute force.
  bool segment_meets_surface(const glm::dvec3& from, const glm::dvec3& to) const;
  std::size_t triangle_count() const noexcept;

 private:
  struct Triangle {
    glm::dvec3 a, b, c;
    glm::dvec3 normal;      // cross(b - a, c - a), not normalised
    glm::dvec3 na, nb, nc;  // unit vertex normals (the face's where the mesh has none)
  };
  struct ProjectionGrid {  // triangles by the cell of their projection along `axis`
    int axis = 0;
    glm::dvec2 origin{0.0}, cell{1.0};
    int cells = 1;
    std::vector<std::vector<std::uint32_t>> bins;
  };
  struct CellGrid {  // triangles by the 3D cells their bounds cover
    glm::dvec3 origin{0.0};
    double cell = 1.0;
    glm::ivec3 size{1};
    std::vector<std::uint32_t> offsets;  // cell -> first entry; size cells + 1
    std::vector<std::uint32_t> entries;  // triangle indices, grouped by cell
  };
  struct Part {  // one object
    std::vector<Triangle> triangles;
    ProjectionGrid projections[3];
    CellGrid cells;
  };

  static Part make_part(const SceneObject& object);
  static int axis_winding(const Part& part, const ProjectionGrid& grid, glm::dvec3 p);
  static int part_winding(const Part& part, const glm::dvec3& p);
  struct Away {  // triangles within radius_mm of `from` left out; radius 0: none
    glm::dvec3 from{0.0};
    double radius_mm = 0.0;
  };
  static Nearest part_nearest(const Part& part, const glm::dvec3& p, double max_distance_mm,
                              const Away& away);

  std::vector<Part> parts_;
  double cap_;
};

// The smooth surface make_bumpy_sphere samples: radius(u) = r + b sin(15 x) sin(15 y) sin(15 z + 0.7)
// for a unit direction u = (x, y, z).
class BumpySphereOracle final : public SurfaceOracle {
 public:
  BumpySphereOracle(float radius_mm, float bump_mm) : radius_mm_(radius_mm), bump_mm_(bump_mm) {}
  // Throws palpate::Error when a vertex of `mesh` is more than 1e-3 mm off the surface, so that a change
  // of the generator cannot silently change what the checks measure.
  void verify(const Mesh& mesh) const;
  double radius_at(glm::dvec3 unit_direction) const noexcept;
  // Signed distance below the surface (positive inside), to first order: g / |grad g| with
  // g(p) = radius(p / |p|) - |p|. Within 1 mm of the surface it agrees with MeshOracle on the mesh to
  // 0.1 mm at 22,952 triangles (0.02 mm at 137,708), under the checks' 0.2 and 0.5 mm.
  double depth_mm(glm::vec3 p) const override;
  // The outward unit normal of the surface through the level of `near_surface`.
  glm::dvec3 outward_normal(glm::dvec3 near_surface) const override;
  // The whole surface's nearest point, |depth_mm(p)|: where the bumps' curvature radius (about 7 mm)
  // exceeds the depth, the nearest point is unique and near `around` for a proxy that keeps up.
  double distance_near(glm::dvec3 p, glm::dvec3 around, double reach_mm) const override;
  float radius_mm() const noexcept { return radius_mm_; }

 private:
  double implicit(glm::dvec3 p) const noexcept;
  glm::dvec3 gradient(glm::dvec3 p) const noexcept;
  float radius_mm_, bump_mm_;
};

}  // namespace palpate::testing
