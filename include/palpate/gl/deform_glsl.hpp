#pragma once
// The paper's deformation as GLSL that an OpenGL application includes in its own shaders, and the
// std140 uniform block that feeds it. palpate's own Renderer uses the same source.
//
// One space for everything: world millimetres, in both shader stages (the paper used eye space; world
// space lets the dents stay put while the camera moves, and needs no view matrix in the block).
//
// In the application's vertex shader (world_normal of unit length):
//     vec3 rest = (model * vec4(position, 1.0)).xyz;           // undeformed world position
//     vec3 world = palpate_displace(rest, world_normal);       // V' = V - N * sum G(|V - c|)
//     pass `rest` and `world_normal` to the fragment stage
// In its fragment shader:
//     vec3 n = palpate_perturb_normal(world_normal_in, rest_in);  // unit, tilted into each dent
// or, to light the displaced position without passing it as a third vector,
//     vec3 p = rest_in, n = world_normal_in;
//     palpate_deform_fragment(p, n);                           // p displaced, n perturbed
// On the host, once: `DeformBlock block; block.attach(program);` and each frame:
//     `block.update(dents); block.bind();` before drawing. The CPU twins of both functions are
// palpate::displaced_position and palpate::perturbed_normal (palpate/core/deform.hpp); tests hold them
// together.
#include <epoxy/gl.h>

#include <cstddef>
#include <cstdint>
#include <glm/vec4.hpp>
#include <span>
#include <string>
#include <string_view>

#include "palpate/core/deform.hpp"

namespace palpate::gl {

// The GLSL source (GLSL 3.30 or later, no #version line): the uniform block `PalpateDeform`,
// `vec3 palpate_displace(vec3 world_position, vec3 world_normal)` for the vertex stage and
// `vec3 palpate_perturb_normal(vec3 world_normal, vec3 rest_world_position)` and
// `void palpate_deform_fragment(inout vec3 world_position, inout vec3 world_normal)` for the fragment stage.
// Both functions compile in either stage. They loop over PALPATE_DENT_SLOTS slots (default
// max_dents), which a shader may #define before this source (insert_deform_glsl does).
std::string_view deform_glsl() noexcept;

// `shader_source` with deform_glsl() inserted right after its `#version` line (or in front, when it
// has none), serving up to `dent_slots` dents (1..max_dents, PALPATE_DENT_SLOTS). The block is read
// at constant offsets, slot by slot; on a GPU a slot past the current count costs a uniform branch,
// on a software rasterizer (llvmpipe) a whole dent, so ask for no more slots than needed. Allocates.
std::string insert_deform_glsl(std::string_view shader_source, int dent_slots = max_dents);

inline constexpr const char* deform_block_name = "PalpateDeform";

// The std140 layout of `PalpateDeform`, member for member. Derived per-dent values are computed
// once on the CPU so that each vertex and fragment pays only for what varies.
struct DeformBlockData {
  glm::vec4 center_depth[max_dents];  // xyz contact point c (world mm), w penetration p (mm)
  glm::vec4 shape[max_dents];         // x (cutoff 4 sigma)^2 (mm^2), y 1/(2 sigma^2) (1/mm^2),
                                      // z p / sigma^2 (1/mm, the slope factor), w sigma (mm)
  std::int32_t count;                 // dents in use, 0..max_dents
  std::int32_t padding[3];
};
static_assert(offsetof(DeformBlockData, center_depth) == 0);
static_assert(offsetof(DeformBlockData, shape) == 16 * max_dents);
static_assert(offsetof(DeformBlockData, count) == 32 * max_dents);
static_assert(sizeof(DeformBlockData) == 32 * max_dents + 16);

// Fills the block from `dents`: the first max_dents are taken, the rest dropped.
DeformBlockData make_deform_block_data(std::span<const Dent> dents) noexcept;

// Owns the uniform buffer of one `PalpateDeform` block (one per object when objects have different
// dents). Needs a current OpenGL context for all of its life.
class DeformBlock {
 public:
  static constexpr GLuint default_binding = 3;

  explicit DeformBlock(GLuint binding = default_binding);
  ~DeformBlock();
  DeformBlock(DeformBlock&& other) noexcept;
  DeformBlock& operator=(DeformBlock&& other) noexcept;
  DeformBlock(const DeformBlock&) = delete;
  DeformBlock& operator=(const DeformBlock&) = delete;

  // Points `program`'s PalpateDeform block at this block's binding point. Throws palpate::Error when
  // the program has no such block (e.g. the snippet was not included, or no function of it is used).
  void attach(GLuint program) const;
  // Uploads the dents (at most max_dents; returns how many were dropped). No allocation.
  int update(std::span<const Dent> dents) noexcept;
  // glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer): also sets the generic GL_UNIFORM_BUFFER
  // binding, as glBindBufferBase does.
  void bind() const noexcept;

  GLuint buffer() const noexcept { return buffer_; }
  GLuint binding() const noexcept { return binding_; }

 private:
  GLuint buffer_ = 0;
  GLuint binding_ = default_binding;
};

}  // namespace palpate::gl
