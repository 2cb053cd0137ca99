#pragma once
// The haptic spring-damper between the proxy (SCP) and the tool tip (HIP).
#include <glm/vec3.hpp>

#include "palpate/core/contact.hpp"
#include "palpate/core/material.hpp"

namespace palpate {

struct ForceResult {
  glm::vec3 force_n{0.0f};     // newtons, world frame
  bool clamped = false;        // the magnitude was cut to max_force_n
  bool invalid_input = false;  // a non-finite input: the force is zero
};

// F = k (SCP - HIP) - b v_n n: the spring pulls the tip toward the proxy; the damper resists the tip's
// velocity along the contact normal only (v_n = v . n), so sliding feels frictionless. A surface pushes
// and never pulls: the component along n is held at >= 0 (a fast withdrawal would otherwise let the
// damper suck the tip back in). The magnitude is clamped to max_force_n.
// Units: k = material.stiffness_n_per_mm (N/mm), positions mm, b = material.damping_ns_per_m (N s/m),
// velocity mm/s (b v is converted from N s/m * mm/s to N).
// No contact gives zero force. Any non-finite input (HIP, SCP, normal, velocity, k, b, limit) gives
// zero force and invalid_input = true. noexcept and allocation-free: safe in the haptic tick.
ForceResult spring_damper(const Contact& contact, glm::vec3 hip_velocity_mm_per_s, const Material& material,
                          float max_force_n) noexcept;

}  // namespace palpate
