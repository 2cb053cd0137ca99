#pragma once
// The cost of palpate's deformation inside the toolkits applications draw with: VTK (an actor with
// palpate's shader replacements) and Coin3D (palpate's shader node), each drawing a scene plainly and
// deformed, interleaved, against its own plain drawing.
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "interleaved.hpp"
#include "palpate/core/contact.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::cli {

struct ToolkitView {
  glm::vec3 eye, center;  // world mm; z up
  float fov_rad, near_mm, far_mm;
  int width, height;
};

struct ToolkitTally {
  std::string toolkit;  // "coin", "vtk"
  std::string variant;  // "plain", "deform"
  Tally tally;
};

// Coin3D on a headless compatibility context of its own; VTK in an offscreen X window, only when an X
// display is there (else a line says so and its rows are left out). Leaves another context current.
std::vector<ToolkitTally> bench_toolkits(const Scene& scene, const ToolkitView& view, const Contact& contact,
                                         double seconds, int rounds);

}  // namespace palpate::cli
