#pragma once
// The deformation of the paper (Luciano, Banerjee, Rizzi 2007), on the CPU: the reference that the
// GLSL in palpate/gl/deform_glsl.hpp computes too, formula for formula (tests hold them together).
//
// All positions are in one space, world millimetres, in both shader stages and here.
// Convention: the dent follows the tool. A vertex V with unit normal N moves to V' = V - N * sum G_i,
// G(d) = p * exp(-d^2 / 2 sigma^2), d = |V - c| the distance of the undeformed vertex to the contact
// point c, p the penetration; at c the surface reaches the HIP. Dents add up.
// Beyond `dent_cutoff_sigmas` sigma a dent is skipped (G < 3.4e-4 p there), here and in the shaders.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <span>

#include "palpate/core/contact.hpp"
#include "palpate/core/mesh.hpp"

namespace palpate {

// One contact as the renderer sees it: where, how deep, and the sigma of the object it deforms.
struct Dent {
  glm::vec3 center_mm{0.0f};  // contact point c (the SCP), world mm
  float depth_mm = 0.0f;      // p
  float sigma_mm = 1.0f;      // spread of the touched object's material
};

inline constexpr int max_dents = 8;
inline constexpr float dent_cutoff_sigmas = 4.0f;

// G(d) = p exp(-d^2 / 2 sigma^2)
float dent_gaussian(float d, float depth_mm, float sigma_mm) noexcept;
// G'(d) = -p d / sigma^2 exp(-d^2 / 2 sigma^2) (the paper's exponent has a sign typo)
float dent_slope(float d, float depth_mm, float sigma_mm) noexcept;

// Sum of G over the dents at `v` (world), honouring the cutoff.
float dent_displacement(glm::vec3 v, std::span<const Dent> dents) noexcept;

// V' = V - N * sum G
glm::vec3 displaced_position(glm::vec3 v, glm::vec3 n, std::span<const Dent> dents) noexcept;

// The paper's per-fragment normal: for each dent, N is rotated about W = N x VC by
// theta = atan(-G'(d)) toward the contact point (the paper's printed rotation tilts away from it, which
// suits a bump, not our dent). cos(atan t) and sin(atan t) are taken as 1/sqrt(1+t^2) and t/sqrt(1+t^2).
// `v` is the undeformed position, the same d as the vertex stage. Guarded at d = 0 and where N || VC.
glm::vec3 perturbed_normal(glm::vec3 n0, glm::vec3 v, std::span<const Dent> dents) noexcept;

// CPU reference of a whole object: its mesh taken to world by the rigid `transform`, displaced by the
// dents along its directions (Mesh::directions, or its normals), with the exact area-weighted vertex
// normals of the deformed triangles. Allocates `out`.
void deform_mesh(const Mesh& mesh, const glm::mat4& transform, std::span<const Dent> dents, Mesh& out);

// The dent as seen in another space, for hosts whose shaders work there (eye space, metres, ...): the
// formulas hold in any one space, as long as positions, directions and dents are all in it.
// `to_space` maps world millimetres to that space: a rotation and translation with, at most, a uniform
// scale (a view matrix times 0.001 for a host in metres). The centre is mapped; depth and sigma are
// scaled by the matrix's scale.
Dent dent_in_space(const Dent& dent, const glm::mat4& to_space) noexcept;

// The dent a contact makes on an object of spread `sigma_mm`.
inline Dent dent_from_contact(const Contact& contact, float sigma_mm) noexcept {
  return Dent{contact.point_mm, contact.depth_mm, sigma_mm};
}

}  // namespace palpate
