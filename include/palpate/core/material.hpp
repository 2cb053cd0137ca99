#pragma once
// How an object deforms, feels and looks.
#include <glm/vec3.hpp>

namespace palpate {

struct Material {
  float sigma_mm = 8.0f;                // spread of the Gaussian dent (standard deviation), mm
  float stiffness_n_per_mm = 0.5f;      // haptic spring k, N/mm
  float damping_ns_per_m = 1.0f;        // haptic damper b, N·s/m
  glm::vec3 color{0.85f, 0.75f, 0.7f};  // linear RGB, used where the mesh has no vertex colors
  bool touchable = true;                // the haptic proxy collides with it
  bool visible = true;                  // the renderer draws it
};

}  // namespace palpate
