#pragma once
// A random wave on the unit sphere: a sum of the spherical harmonics of one degree with pseudo-random
// coefficients. Its zero lines meander like the sulci of a cortex, at one spacing everywhere, with no
// preferred direction (Berry's random wave model). Private to palpate_core.
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace palpate::detail {

class SphericalWave {
 public:
  // `degree` in [1, 64]. The coefficients come from `seed` through splitmix64: the same on every machine.
  SphericalWave(int degree, std::uint64_t seed);

  struct Sample {
    double value = 0.0;
    glm::dvec3 gradient{0.0};  // on the unit sphere: tangent to it, per radian
  };
  // `direction` must be unit length. Plain arithmetic only (no libm): deterministic. No allocation.
  Sample operator()(glm::dvec3 direction) const noexcept;

  // sqrt(l (l + 1)): the wave satisfies laplacian(f) = -wavenumber^2 f on the unit sphere, so locally it
  // oscillates like a plane wave of this many radians per radian.
  double wavenumber() const noexcept { return wavenumber_; }
  // The root mean square of the value over the sphere (and over seeds): the same at every point.
  double rms() const noexcept { return rms_; }

 private:
  int degree_;
  double wavenumber_;
  double rms_;
  std::vector<double> cos_coefficient_;  // per order m, normalisation folded in
  std::vector<double> sin_coefficient_;
  // The Legendre recurrence's factors for each step k < degree and order m <= k, row by row in k.
  std::vector<double> z_factor_, previous_factor_;
};

}  // namespace palpate::detail
