#pragma once
// The deformation of the paper (Luciano, Banerjee, Rizzi 2007), on the CPU: the reference that the
// GLSL in palpate/gl/deform_glsl.hpp computes too, formula for formula (tests hold them together).
//
// All positions are in one space, world millimetres, in both shader stages and here.
// Convention: the dent follows the tool. A vertex V with unit normal N moves to V' = V - N * sum G_i,
// G(d) = p * exp(-d^2 / 2 sigma^2), d = |V - c| the distance of the undeformed vertex to the contact
// point c, p the penetration; at c the surface reaches the HIP. Dents add up.
// Beyond `dent_cutoff_sigmas` sigma a dent is skipped (G < 3.4e-4 p there), here and in the shaders.
//
// The geodesic falloff (beyond the paper): a dent marked `along_surface` measures d along the surface
// instead of through the air, from a per-vertex sample (SurfacePatch, palpate/core/surface_patch.hpp):
// xyz the unit direction toward the contact along the surface, w the distance along it. Interpolated
// inside a triangle, that distance would overestimate near the contact (the distance is a cone there,
// the interpolation a plane), so the shaders interpolate what the surface adds to the straight line
// instead: with s the sample's distance, u its direction, e = |V - c| and VC = c - V at the vertex,
//     beyond = (u s - VC, s - e),     d = |P - c| + beyond.w,   toward = (c - P) + beyond.xyz
// at a point P, `beyond` interpolated from the corners: at a vertex d = s exactly, near the contact
// (where the surface is the contact's plane) beyond is zero and d the straight line. SurfacePatch writes
// s >= e at every vertex it reaches along the surface, so there d is never shorter than the straight
// line; only where a wall behind the dent gives way further than the straight line's Gaussian would move
// it is s < e (SurfacePatch::PushedDent). The tilt of the normal follows `toward` (w'(d) times the
// distance's gradient). Only the first dent of an object can fall off along the surface (one patch per
// object); later dents use the straight line.
// Such a dent also pushes every vertex one way, along -`normal` (the contact's outward normal), as
// H3DAPI's deformer does, instead of each vertex along its own direction: moved along their own
// normals, the vertices of a convex crown cross once the depth passes its radius of curvature (on the
// Colin27 brain at sigma 4 mm and 2 sigma deep, ten times the self-intersecting triangles:
// docs/design.md). The shading normal is then that of the surface V - n G(V):
//     N' = N + (N x grad G) x n,   grad G = G'(d) grad d   (N + grad G when n = N).
// A zero `normal` keeps each vertex's own direction.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <span>

#include "palpate/core/contact.hpp"
#include "palpate/core/mesh.hpp"

namespace palpate {

// One contact as the renderer sees it: where, how deep, and the sigma of the object it deforms.
struct Dent {
  glm::vec3 center_mm{0.0f};  // contact point c (the SCP), world mm
  float depth_mm = 0.0f;      // p
  float sigma_mm = 1.0f;      // spread of the touched object's material
  // The geodesic falloff: d from the per-vertex surface sample (first dent only; see above).
  bool along_surface = false;
  glm::vec3 normal{0.0f};  // the contact's outward unit normal: the push's direction when along_surface
};

// A vertex's surface sample where no patch reaches: any dent along the surface has zero weight there.
inline constexpr float surface_far_mm = 1.0e6f;
inline constexpr glm::vec4 no_surface_sample{0.0f, 0.0f, 0.0f, surface_far_mm};

// The distance d of `v` from the dent's centre: straight, or blended from the surface sample (above).
float dent_distance(const Dent& dent, glm::vec3 v, glm::vec4 surface_sample) noexcept;

inline constexpr int max_dents = 8;
inline constexpr float dent_cutoff_sigmas = 4.0f;

// G(d) = p exp(-d^2 / 2 sigma^2)
float dent_gaussian(float d, float depth_mm, float sigma_mm) noexcept;
// G'(d) = -p d / sigma^2 exp(-d^2 / 2 sigma^2) (the paper's exponent has a sign typo)
float dent_slope(float d, float depth_mm, float sigma_mm) noexcept;

// Sum of G over the dents at `v` (world), honouring the cutoff; `surface_sample` (in the dents' space)
// serves the first dent where it falls off along the surface.
float dent_displacement(glm::vec3 v, std::span<const Dent> dents,
                        glm::vec4 surface_sample = no_surface_sample) noexcept;

// V' = V - N * sum G
glm::vec3 displaced_position(glm::vec3 v, glm::vec3 n, std::span<const Dent> dents,
                             glm::vec4 surface_sample = no_surface_sample) noexcept;

// The paper's per-fragment normal: for each dent, N is rotated about W = N x VC by
// theta = atan(-G'(d)) toward the contact point (the paper's printed rotation tilts away from it, which
// suits a bump, not our dent). cos(atan t) and sin(atan t) are taken as 1/sqrt(1+t^2) and t/sqrt(1+t^2).
// `v` is the undeformed position, the same d as the vertex stage. Guarded at d = 0 and where N || VC.
// A dent along the surface tilts toward the contact along the surface (the sample's direction).
glm::vec3 perturbed_normal(glm::vec3 n0, glm::vec3 v, std::span<const Dent> dents,
                           glm::vec4 surface_sample = no_surface_sample) noexcept;

// CPU reference of a whole object: its mesh taken to world by the rigid `transform`, displaced by the
// dents along its directions (Mesh::directions, or its normals), with the exact area-weighted vertex
// normals of the deformed triangles. `surface_samples` (object frame, one per vertex, or none) serve a
// first dent along the surface. Allocates `out`.
void deform_mesh(const Mesh& mesh, const glm::mat4& transform, std::span<const Dent> dents, Mesh& out,
                 std::span<const glm::vec4> surface_samples = {});

// The dent as seen in another space, for hosts whose shaders work there (eye space, metres, ...): the
// formulas hold in any one space, as long as positions, directions and dents are all in it.
// `to_space` maps world millimetres to that space: a rotation and translation with, at most, a uniform
// scale (a view matrix times 0.001 for a host in metres). The centre is mapped; depth and sigma are
// scaled by the matrix's scale (a surface sample goes with surface_sample_in_space).
Dent dent_in_space(const Dent& dent, const glm::mat4& to_space) noexcept;
// A surface sample of the object frame in that space: its direction rotated by `to_space`'s rotation,
// its distance scaled by its scale (`to_space` from the object frame, as for the positions).
glm::vec4 surface_sample_in_space(glm::vec4 sample, const glm::mat4& to_space) noexcept;

// The dent widened where it is deeper than its spread allows: sigma grown to p e^(-1/2) / max_slope
// where needed, so that its steepest slope |G'| = p e^(-1/2) / sigma stays at most `max_slope`. A
// surface pushed one way (Dent::normal) turns over where the slope along it passes 1.
Dent dent_with_slope_limit(const Dent& dent, float max_slope) noexcept;
// The slope limit of a dent that falls off along the surface and pushes one way: below it, presses up
// to 3 sigma on the real brain leave no triangle turned over (docs/design.md).
inline constexpr float surface_dent_max_slope = 0.75f;

// The dent a contact makes on an object of spread `sigma_mm`.
inline Dent dent_from_contact(const Contact& contact, float sigma_mm) noexcept {
  return Dent{contact.point_mm, contact.depth_mm, sigma_mm};
}

}  // namespace palpate
