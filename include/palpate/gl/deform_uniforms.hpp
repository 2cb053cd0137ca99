#pragma once
// Feeds the dents to an application's shader program that includes deform_glsl(): a uniform buffer
// for the block dialect (OpenGL 3.1 and later, no DSA needed), glUniform4fv for the arrays (OpenGL
// 2.1). Works whatever GL loader the application uses (palpate loads its few functions privately) and
// includes no GL header: GL names are plain integers here.
//
//     palpate::gl::DeformUniforms dents(program);      // once, after linking (throws palpate::Error)
//     ...each frame:
//     dents.set({&dent, 1});                           // the latest dents, in the shader's space
//     glUseProgram(program);
//     dents.apply();                                   // with the program in use, before drawing
//
// Needs the program's context current when made, set and applied; destroyed after the context has
// gone (glfwTerminate first), it leaves the buffer to the context's end. Not thread-safe.
#include <cstdint>
#include <span>

#include "palpate/core/deform.hpp"
#include "palpate/gl/deform_glsl.hpp"

namespace palpate::gl {

class DeformUniforms {
 public:
  // The uniform-buffer binding point the block uses unless told otherwise.
  static constexpr std::uint32_t default_binding = 3;

  // For `program`, made with insert_deform_glsl (either dialect) and linked. Throws palpate::Error when
  // the program did not link (with its info log), or has neither the `PalpateDeform` block nor the
  // `palpate_dent_*` arrays active (the snippet not included, or none of its functions used).
  // Allocates a buffer for the block dialect.
  explicit DeformUniforms(std::uint32_t program, std::uint32_t block_binding = default_binding);
  ~DeformUniforms();
  DeformUniforms(DeformUniforms&& other) noexcept;
  DeformUniforms& operator=(DeformUniforms&& other) noexcept;
  DeformUniforms(const DeformUniforms&) = delete;
  DeformUniforms& operator=(const DeformUniforms&) = delete;

  // Takes the dents for the next apply() (the block dialect uploads them into its buffer now, leaving
  // the GL_UNIFORM_BUFFER binding as it was). At most max_dents; returns how many were dropped. No
  // allocation.
  int set(std::span<const Dent> dents) noexcept;
  // With the program in use (glUseProgram): binds the block's buffer to its binding point (the generic
  // GL_UNIFORM_BUFFER binding is left as found), or sets the arrays' uniforms. No allocation.
  void apply() const noexcept;

  GlslDialect dialect() const noexcept { return dialect_; }
  std::uint32_t program() const noexcept { return program_; }
  std::uint32_t buffer() const noexcept { return buffer_; }  // 0 for the arrays
  std::uint32_t binding() const noexcept { return binding_; }

 private:
  std::uint32_t program_ = 0;
  GlslDialect dialect_ = GlslDialect::uniform_block;
  std::uint32_t buffer_ = 0, binding_ = default_binding;
  std::int32_t center_depth_location_ = -1, shape_location_ = -1, count_location_ = -1;  // arrays only
  std::int32_t surface_dent_location_ = -1, surface_normal_location_ = -1;
  DeformBlockData data_{};
};

}  // namespace palpate::gl
