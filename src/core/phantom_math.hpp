#pragma once
// Smooth blending helpers for the phantom generators. Private to palpate_core.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/phantom.hpp"

namespace palpate::detail {

// Throws palpate::Error naming the generator when it is asked for fewer than phantom_min_vertices.
inline void require_phantom_vertices(const char* generator, std::size_t vertices) {
  if (vertices < phantom_min_vertices) {
    throw Error(std::string(generator) + ": need at least " + std::to_string(phantom_min_vertices) +
                " vertices, got " + std::to_string(vertices));
  }
}

// 0 below edge0, 1 above edge1 (or the reverse when edge0 > edge1), C1 in between.
inline double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// min / max with the corner rounded over `k` (polynomial smooth min): C1, exact when |a - b| >= k, and
// never more than k / 4 from the hard value.
inline double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}
inline double smooth_max(double a, double b, double k) {
  return -smooth_min(-a, -b, k);
}

// A bell of height 1 at d2 = 0 that vanishes for d2 >= 4, shaped like exp(-d2) near its top (d2: a
// squared distance in units of the bell's width). Plain arithmetic, so the same on every machine.
inline double bell(double d2) {
  const double t = std::max(0.0, 1.0 - 0.25 * d2);
  return (t * t) * (t * t);
}

}  // namespace palpate::detail
