#pragma once
// How an object deforms, feels and looks.
#include <glm/vec3.hpp>

namespace palpate {

// How far a dent reaches: through the air, as in the paper (a press on one bank of a sulcus dents the
// facing bank too), or along the surface (palpate/core/surface_patch.hpp; the renderer's cost: a march
// over the patch each frame).
enum class Falloff { euclidean, geodesic };

struct Material {
  float sigma_mm = 8.0f;                 // spread of the Gaussian dent (standard deviation), mm
  float stiffness_n_per_mm = 0.5f;       // haptic spring k, N/mm
  float damping_ns_per_m = 1.0f;         // haptic damper b, N·s/m
  glm::vec3 color{0.85f, 0.75f, 0.7f};   // linear RGB, used where the mesh has no vertex colors
  bool touchable = true;                 // the haptic proxy collides with it
  bool visible = true;                   // the renderer draws it
  Falloff falloff = Falloff::euclidean;  // how the renderer spreads its dents
};

// The paper's two materials: brain dents locally (its Fig. 1), skin spreads a dent widely and is
// stiffer (its Fig. 3).
inline constexpr Material brain_material{
    .sigma_mm = 5.0f, .stiffness_n_per_mm = 0.3f, .damping_ns_per_m = 1.0f, .color = {0.88f, 0.62f, 0.60f}};
inline constexpr Material skin_material{
    .sigma_mm = 14.0f, .stiffness_n_per_mm = 0.8f, .damping_ns_per_m = 1.0f, .color = {0.93f, 0.76f, 0.64f}};

}  // namespace palpate
