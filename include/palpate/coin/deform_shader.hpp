#pragma once
// palpate's deformation inside Coin3D (Open Inventor, the paper's own scene graph): an SoShaderProgram
// with GLSL 1.20 vertex and fragment shaders that displace the shapes under it and tilt their normals,
// fed through SoShaderParameter fields. The shaders light as Coin's fixed function does (the scene's
// SoMaterial, per-vertex colours, and its directional, point and spot lights through
// gl_LightSource), per vertex or per fragment, so the dent reads under the scene's own lights.
//
//     palpate::coin::DeformShader dent;                  // SoDB::init() first (done here if not)
//     separator->insertChild(dent.node(), 0);            // before the shapes it deforms
//     ...each frame (from the haptic loop's latest contact, or the host's own haptics):
//     dent.set({&object_dent, 1});                       // in the shapes' own coordinates
//
// The dents are in the coordinates the shapes' vertices are given in (their SoCoordinate3 points),
// as the paper passes its contact to the shader; palpate::dent_in_space (palpate/core/deform.hpp) takes
// a world dent there through the inverse of the shapes' transform. The vertices move along their
// normals (give the shapes per-vertex normals: SoNormal with PER_VERTEX_INDEXED binding, or Coin's
// smooth ones); lighting is one-sided, as Coin's default SoShapeHints; textures are not applied.
// Not thread-safe: set() on the thread that renders (it writes fields of the scene graph).
#include <Inventor/nodes/SoShaderProgram.h>

#include <memory>
#include <span>

#include "palpate/core/deform.hpp"

namespace palpate::coin {

struct DeformShaderParams {
  int dent_slots = 1;  // dents at most per render, 1..max_dents (each costs every fragment on llvmpipe)
  int lights = 1;      // how many of the scene's lights to light with (Coin numbers them from 0 in order)
  // Lighting: per vertex as Coin's fixed function lights (each vertex with the true normal of the
  // deformed surface), or per fragment within the dents' reach (the normal tilted at each fragment: a
  // smooth dent on a coarse mesh too, at the cost of every fragment on a software rasterizer).
  bool per_fragment = false;
};

class DeformShader {
 public:
  // Throws palpate::Error for slots or lights out of range (lights: 1..8).
  explicit DeformShader(DeformShaderParams params = {});
  ~DeformShader();  // the scene graph keeps the node alive while it holds it
  DeformShader(const DeformShader&) = delete;
  DeformShader& operator=(const DeformShader&) = delete;

  // The node to insert before the shapes to deform.
  SoShaderProgram* node() const noexcept;

  // The dents for the next render. Returns how many were dropped (beyond the slots).
  int set(std::span<const Dent> dents);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace palpate::coin
