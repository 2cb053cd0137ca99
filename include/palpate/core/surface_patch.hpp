#pragma once
// The per-vertex data of the geodesic falloff: for the vertices a dent reaches along the surface (its
// patch, out to 4 sigma), the distance from the contact over the surface and the unit direction toward
// the contact along it, as the surface samples the deformation reads (palpate/core/deform.hpp); every
// other vertex holds no_surface_sample, where the dent's weight is zero.
//
// Each frame, compute() marches over the undeformed mesh from the contact (GeodesicField) and rewrites
// the samples of the last patch and the new one only; changed() says which vertices to upload. Vertices
// split at one position (flat shading, creases) are welded for the march, so the front crosses their
// seams, and every copy gets the same sample.
//
// A dent pushes every vertex one way (against the contact's normal). Where it is deeper than a wall
// behind or beside it is thick, the dented surface would pass through that wall, which the surface
// distance cannot know; given the dent's depth, compute() lets such walls give way (see PushedDent).
//
//     palpate::SurfacePatch patch(mesh);                  // once: adjacency, workspace, a BVH
//     ...each frame, for the object's first dent (object frame):
//     dent = palpate::dent_with_slope_limit(dent, palpate::surface_dent_max_slope);
//     patch.compute(contact_triangle, contact_point, {dent.depth_mm, dent.sigma_mm});
//     upload patch.samples()[changed.first, changed.first + changed.count) into the vertex attribute
//     dent.along_surface = true;
//     dent.normal = the rotation to the dent's space * patch.contact_normal();
#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <optional>
#include <span>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/deform.hpp"
#include "palpate/core/displacement.hpp"
#include "palpate/core/geodesic.hpp"
#include "palpate/core/mesh.hpp"

namespace palpate {

class SurfacePatch {
 public:
  // A range of vertices [first, first + count).
  struct Range {
    std::uint32_t first = 0, count = 0;
  };

  // A dent of depth p and spread sigma (object frame; sigma as widened by dent_with_slope_limit) that
  // pushes every vertex against contact_normal(). Where a point the dent moves by G lies t in front of
  // a wall along the push, the wall there moves to G - 0.8 t, unless it is already at G - 0.85 t or
  // more (exactly, over the two triangles' overlap seen along the push): the wall gives way ahead of the
  // dent, keeping at least 0.15 of the gap, and so do walls behind it in turn. A triangle the pushes would
  // turn over has its corners further along the push raised. No vertex moves past the straight line's
  // Gaussian at wall_reach_edges of its longest edges nearer the contact; its distance becomes the one at
  // which the dent's Gaussian gives its push: shorter than the distance along the surface, and shorter than
  // the straight line only at a wall's vertex that gives way further than the straight line's Gaussian would
  // move it, so the shaders need nothing more.
  struct PushedDent {
    float depth_mm = 0.0f, sigma_mm = 0.0f;
    bool operator==(const PushedDent&) const = default;
  };
  static constexpr float wall_gap_slope = 0.8f;
  // A wall's corner is left where it is when it keeps 0.15 of the gap: two walls that each lie behind
  // the other somewhere (sheets nearly along the push) raised each other in turn by ever smaller steps,
  // each 0.72 of the one before, 50 times a vertex (the slowest of the tests' 20 presses of 3 sigma on
  // the SPM12 cortex: 16 ms, 5 ms with it).
  static constexpr float wall_gap_slope_enough = 0.85f;
  static constexpr float wall_reach_edges = 2.0f;
  // The distances are exact out to 2 sigma or as far as this many windows reach (GeodesicField::Reach):
  // their number grows faster than the area; at sigma 4 mm 1,500 reach 2 sigma on the Colin27 brain,
  // 4,000-7,000 on the phantom's densest folds (up to 1.4 ms), where the march that goes on from there,
  // its error shrinking with the edges, does least harm. Against CGAL (60 contacts a row, four cortices,
  // sigma 2 / 4 / 8 mm) the largest weight error is 0.015 of p at sigma 2 and 4 mm with or without the
  // budget; at sigma 8 mm, where 2 sigma takes the most windows, 0.026 with it (0.022 with 4,000, 0.008
  // with none).
  static constexpr std::size_t window_budget = 3000;

  // Copies what it needs of `mesh` (its positions and triangles, welded by position) and builds a BVH of
  // it for the walls, with each triangle's clearances, all round and behind it (0.8-0.85 s for the 137,854
  // triangles of the Colin27 brain on the development VM). Allocates.
  explicit SurfacePatch(const Mesh& mesh);
  SurfacePatch(const SurfacePatch&) = delete;  // its field refers to its own welded mesh
  SurfacePatch& operator=(const SurfacePatch&) = delete;

  // The patch of a dent at `point_mm` (object frame) on triangle `triangle` of the mesh, out to
  // `radius_mm` along the surface. A triangle out of range (-1: unknown) is found as the one closest to
  // the point, by a scan of the whole mesh (about 1 ms per 100,000 triangles): pass it when known. No
  // allocation.
  void compute(std::int64_t triangle, glm::vec3 point_mm, float radius_mm) noexcept;
  // The patch of `dent` out to 4 sigma, with the walls it would pass through given way (PushedDent). No
  // allocation, unless a press looks at more walls than the mesh has triangles (8 mm presses at sigma
  // 8 mm on Colin27 look at 26,000 at most of 137,854). The same press as the last (a press held still)
  // is not computed again: changed() is then empty.
  void compute(std::int64_t triangle, glm::vec3 point_mm, PushedDent dent) noexcept;
  // No dent: the last patch goes back to no_surface_sample. No allocation.
  void clear() noexcept;

  // One sample per vertex of the mesh (object frame).
  std::span<const glm::vec4> samples() const noexcept { return samples_; }
  // The vertices whose samples the last compute() or clear() rewrote: the last patch and the new one.
  Range changed() const noexcept { return changed_; }
  // The contact triangle's outward unit normal, object frame (Dent::normal once taken to world).
  glm::vec3 contact_normal() const noexcept { return contact_normal_; }
  // How much further than a dent's 4 sigma from the contact, in a straight line, it may move a corner of
  // the mesh's triangle `triangle`: as a wall's corner, up to wall_reach_edges of the corner's longest
  // edges (wall_push_cap). 0 for a triangle out of range.
  float wall_reach_mm(std::uint32_t triangle) const noexcept;
  // The furthest from the contact, in a straight line, of the vertices the last compute() gave a sample
  // (0: none).
  float moved_reach_mm() const noexcept { return moved_reach_mm_; }
  // Vertices (welded) in the current patch, and those of them that gave way as walls.
  std::size_t size() const noexcept { return patch_.size(); }
  std::size_t walls_given_way() const noexcept { return walls_; }

 private:
  SurfacePatch(const Mesh& mesh, PositionGroups groups);
  std::uint32_t closest_triangle(glm::vec3 point_mm) const noexcept;
  void stamp_two_rings(std::uint32_t welded_vertex, std::vector<std::uint32_t>& stamps,
                       std::uint32_t stamp) const;
  float clearance(std::uint32_t welded_vertex, std::vector<std::uint32_t>& stamps, std::uint32_t stamp) const;
  float clearance_behind(std::uint32_t triangle, std::vector<std::uint32_t>& stamps,
                         std::uint32_t stamp) const;
  void march(std::int64_t triangle, glm::vec3 point_mm, float radius_mm) noexcept;
  struct Frame {  // the push and two directions across it
    glm::vec3 push, across, across2;
  };
  struct Corners {  // a triangle's corners: seen along the push, how deep along it, their pushes
    std::uint32_t vertex[3];
    glm::vec2 outline[3];
    float depth[3], push[3];
  };
  Corners corners_of(std::uint32_t triangle, const Frame& frame) const noexcept;
  struct WallPush {  // what a wall's corners move by, and what they may keep without moving
    float least, enough;
  };
  WallPush least_wall_push(const Corners& front, const Corners& wall) const noexcept;
  static float wall_push_cap(float distance_mm, float longest_edge_mm, PushedDent dent) noexcept;
  void upright_share(const Corners& c, const Frame& frame, float along[3], float& upright) const noexcept;
  void give_way(glm::vec3 point_mm, PushedDent dent) noexcept;
  void assign_clusters();
  std::span<const std::uint32_t> walls_met(const Corners& front, float reach_mm,
                                           std::uint32_t cluster) noexcept;
  void gather_walls(std::uint32_t cluster, glm::vec3 point_mm, PushedDent dent, const Frame& frame) noexcept;
  void write_samples(glm::vec3 point_mm, float radius_mm) noexcept;
  void write(std::uint32_t welded_vertex, glm::vec4 sample) noexcept;

  std::vector<std::uint32_t> welded_triangle_;  // per triangle of the mesh: its number in welded_
  Mesh welded_;  // where that is more local: vertices along a space-filling curve, triangles by their lowest
                 // corner
  std::vector<std::uint32_t> first_copy_, copies_;  // the mesh's vertices at each welded vertex
  GeodesicField field_;
  std::vector<glm::vec4> samples_;
  std::vector<glm::vec3> gradient_sum_;  // per welded vertex, scratch
  Bvh walls_bvh_;                        // of welded_
  std::vector<float>
      clearance_mm_;  // per welded triangle: how near the nearest triangle beyond its corners' two rings
  std::vector<float> back_clearance_mm_;  // per welded triangle: the same, behind its plane
  std::vector<float> longest_edge_mm_;    // per welded vertex
  std::vector<float> distance_mm_;        // per welded vertex: the sample's distance; +inf outside the patch
  std::vector<float> push_mm_;            // per welded vertex, scratch: what the dent moves it by
  std::vector<std::uint32_t> pending_;    // per welded vertex, scratch: a ring of vertices to cast from
  std::vector<std::uint8_t> queued_;      // per welded vertex, scratch: whether it is in pending_
  std::vector<std::uint8_t> unsettled_;   // per welded triangle, scratch: whether to look behind it again
  std::vector<std::uint32_t> patch_;      // welded vertices with a sample now
  // The walls' look, shared by the triangles of a small BVH subtree (a cluster): once a press, the first of
  // them to look gathers every triangle the cluster's pushes could reach; each then reads that list.
  struct WallCandidates {  // in arrays of each bound, so that a front tests four or eight at once
    std::vector<std::uint32_t> triangle;
    std::vector<std::array<std::uint32_t, 3>> corners;
    std::vector<float> depth_low, depth_high;    // along the push
    std::vector<float> across_low, across_high;  // seen along it
    std::vector<float> across2_low, across2_high;
    void reserve(std::size_t count);
    void clear() noexcept;
    void push_back(std::uint32_t wall, const Corners& corners_seen);
    std::uint32_t size() const noexcept { return std::uint32_t(triangle.size()); }
  };
  struct Cluster {
    glm::vec3 low, high;    // bounds of its triangles
    float longest_edge_mm;  // of their corners
  };
  std::vector<Cluster> clusters_;
  std::vector<std::uint32_t> cluster_of_;     // per welded triangle
  std::vector<std::uint32_t> cluster_press_;  // per cluster, scratch: the press its list is of
  std::vector<std::uint32_t> cluster_first_;  // per cluster, scratch: where its list starts
  std::vector<std::uint32_t> cluster_count_;  // per cluster, scratch
  WallCandidates wall_candidates_;            // scratch, the lists of this press
  std::vector<std::uint8_t> wall_meets_;      // scratch, per candidate of a cluster: whether a front meets it
  std::vector<std::uint32_t> wall_met_;       // scratch: those it meets
  std::uint32_t press_number_ = 0;
  std::size_t walls_ = 0;
  float moved_reach_mm_ = 0.0f;
  struct Press {
    std::int64_t triangle;
    glm::vec3 point_mm;
    PushedDent dent;
    bool operator==(const Press&) const = default;
  };
  std::optional<Press> last_press_;  // what the samples are of, when a PushedDent compute() made them
  Range changed_;
  glm::vec3 contact_normal_{0.0f};
};

}  // namespace palpate
