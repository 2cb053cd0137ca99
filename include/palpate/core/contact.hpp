#pragma once
// The one value that crosses from the haptic thread to the graphics thread.
#include <cstdint>
#include <glm/vec3.hpp>

namespace palpate {

struct Contact {
  int object = -1;           // scene object index; -1 when not in contact
  int triangle = -1;         // triangle index within that object's mesh
  glm::vec3 point_mm{0.0f};  // surface contact point SCP (the proxy), world mm
  glm::vec3 hip_mm{0.0f};    // haptic interaction point (the tool tip), world mm
  glm::vec3 normal{0.0f};    // outward unit surface normal at the SCP, world
  float depth_mm = 0.0f;     // penetration p = |HIP - SCP|
  std::uint64_t tick = 0;    // haptic tick that produced it
  double time_s = 0.0;       // haptic clock time of that tick, s

  bool in_contact() const noexcept { return object >= 0; }
};

}  // namespace palpate
