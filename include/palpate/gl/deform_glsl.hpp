#pragma once
// The paper's deformation as GLSL that an OpenGL application puts into its own shaders, in the dialect
// of the shader's own #version, and the dent data those shaders read. Needs no OpenGL header, loader
// or context: it is text and numbers (DeformUniforms, in deform_uniforms.hpp, feeds them to a program).
//
// Any one space serves, as long as the positions, the directions and the dents are all in it: world
// millimetres (palpate's renderer), eye space in metres (a GL 2.1 program with gl_ModelViewMatrix and
// no model matrix), ... dent_in_space (palpate/core/deform.hpp) takes a Dent from world millimetres
// into such a space.
//
// In the application's vertex shader:
//     vec3 rest = ...;                                        // the undeformed position, in that space
//     vec3 moved = palpate_displace(rest, direction);         // V' = V - D * sum G(|V - c|)
//     pass `rest` and the normal to the fragment stage
// `direction` is the unit direction a dent moves the vertex: the mesh's normal where its vertices are
// not split, else one direction shared by every corner at a position (Mesh::directions, so that split
// corners move together and the surface does not crack).
// In its fragment shader:
//     vec3 n = palpate_perturb_normal(normal_in, rest_in);   // unit, tilted into each dent
// The CPU twins are palpate::displaced_position and palpate::perturbed_normal (palpate/core/deform.hpp);
// tests hold them together.
//
// The geodesic falloff (a dent spreads along the surface, not through the air): turn each vertex's
// surface sample (palpate::SurfacePatch, palpate/core/surface_patch.hpp: a vec4 attribute, its xyz
// rotated into the shaders' space and its w scaled to its unit, surface_sample_in_space) into what the
// stages interpolate, pass that on to the fragment stage and call the overloads that take it:
//     vec4 surface_out = palpate_surface_varying(rest, surface);
//     vec3 moved = palpate_displace(rest, direction, surface_out);
//     vec3 n = palpate_perturb_normal(normal_in, rest_in, surface_in);   // surface_out, interpolated
// The first dent falls off along the surface where the data says so (Dent::along_surface, set by
// DeformUniforms); the two-argument functions always use the straight line.
#include <cstddef>
#include <cstdint>
#include <glm/vec4.hpp>
#include <span>
#include <string>
#include <string_view>

#include "palpate/core/deform.hpp"

namespace palpate::gl {

// How the dents reach the shader.
enum class GlslDialect {
  uniform_arrays,  // GLSL 1.10 to 1.30 (OpenGL 2.x, 3.0): plain uniform arrays, set with glUniform4fv
  uniform_block,   // GLSL 1.40 and later, and GLSL ES 3.00: a std140 uniform block, from a buffer
};

// The dialect a shader's `#version` line asks for: up to 130 (and no #version at all, which means
// 110) the arrays, from 140 and for "300 es" the block.
GlslDialect dialect_of(std::string_view shader_source) noexcept;

// The GLSL source, without a #version line, serving up to `dent_slots` dents (1..max_dents): the dent
// data (`PalpateDeform` block or `palpate_dent_*` arrays), `vec3 palpate_displace(vec3 position,
// vec3 direction)`, `vec3 palpate_perturb_normal(vec3 normal, vec3 rest_position)`,
// `void palpate_deform_fragment(inout vec3 position, inout vec3 normal)` and `bool
// palpate_reaches(vec3 rest_position)` (to branch around the rest where no dent reaches); each compiles in
// either stage. The loops run over a compile-time number of slots (the data is read at constant offsets): on
// a GPU an unused slot costs a uniform branch, on a software rasterizer (llvmpipe) a whole dent, so ask for
// no more than needed. Allocates.
std::string deform_glsl(GlslDialect dialect, int dent_slots = max_dents);

// `shader_source` with deform_glsl() inserted after its `#version` line and any `#extension` and
// `#pragma` lines that follow it (where the GLSL rules want them), in the dialect of its #version.
// Allocates.
std::string insert_deform_glsl(std::string_view shader_source, int dent_slots = max_dents);
std::string insert_deform_glsl(std::string_view shader_source, int dent_slots, GlslDialect dialect);

inline constexpr const char* deform_block_name = "PalpateDeform";

// The dent data, member for member as the std140 block lays it out (and as the arrays hold it).
// Derived per-dent values are computed once on the CPU so that each vertex and fragment pays only for
// what varies.
struct DeformBlockData {
  glm::vec4 center_depth[max_dents];  // xyz contact point c, w penetration p (lengths in the space's unit)
  glm::vec4 shape[max_dents];         // x (cutoff 4 sigma)^2, y 1/(2 sigma^2), z p / sigma^2, w sigma
  std::int32_t count;                 // dents in use, 0..max_dents
  std::int32_t surface_dent;          // 1: the first dent falls off along the surface
  std::int32_t padding[2];
  glm::vec4 surface_normal;  // xyz: Dent::normal of the first dent, where it falls off along the surface
};
static_assert(offsetof(DeformBlockData, center_depth) == 0);
static_assert(offsetof(DeformBlockData, shape) == 16 * max_dents);
static_assert(offsetof(DeformBlockData, count) == 32 * max_dents);
static_assert(offsetof(DeformBlockData, surface_dent) == 32 * max_dents + 4);
static_assert(offsetof(DeformBlockData, surface_normal) == 32 * max_dents + 16);
static_assert(sizeof(DeformBlockData) == 32 * max_dents + 32);

// Fills the data from `dents`: the first max_dents are taken, the rest dropped. No allocation.
DeformBlockData make_deform_block_data(std::span<const Dent> dents) noexcept;

}  // namespace palpate::gl
