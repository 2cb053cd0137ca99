#include "core/spherical_wave.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "palpate/core/error.hpp"

namespace palpate::detail {
namespace {

// Points spread evenly over the unit sphere (a Fibonacci spiral).
glm::dvec3 spiral_point(int i, int count) {
  const double z = 1.0 - 2.0 * (i + 0.5) / count, phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double s = std::sqrt(1.0 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Tangent directions at u.
glm::dvec3 tangent(glm::dvec3 u) {
  return glm::normalize(glm::cross(u, glm::dvec3(0.3, 0.5, 0.7)));
}

double value(const SphericalWave& wave, glm::dvec3 p) {
  return wave(glm::normalize(p)).value;
}

TEST(SphericalWave, GradientIsTheTangentialDerivative) {
  const SphericalWave wave(15, 42);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 u = spiral_point(i, 200), t1 = tangent(u), t2 = glm::cross(u, t1);
    const SphericalWave::Sample s = wave(u);
    EXPECT_NEAR(glm::dot(s.gradient, u), 0.0, 1e-9);
    constexpr double h = 1e-6;
    const double d1 = (value(wave, u + h * t1) - value(wave, u - h * t1)) / (2.0 * h);
    const double d2 = (value(wave, u + h * t2) - value(wave, u - h * t2)) / (2.0 * h);
    EXPECT_NEAR(glm::dot(s.gradient, t1), d1, 1e-5 * wave.wavenumber());
    EXPECT_NEAR(glm::dot(s.gradient, t2), d2, 1e-5 * wave.wavenumber());
  }
}

TEST(SphericalWave, IsAnEigenfunctionOfTheSphericalLaplacian) {
  // A sum of degree-l harmonics satisfies laplacian(f) = -l (l + 1) f. The Laplacian on the sphere at u:
  // the sum of second derivatives along two orthogonal great circles through u.
  const SphericalWave wave(11, 7);
  EXPECT_DOUBLE_EQ(wave.wavenumber(), std::sqrt(11.0 * 12.0));
  for (int i = 0; i < 100; ++i) {
    const glm::dvec3 u = spiral_point(i, 100), t1 = tangent(u), t2 = glm::cross(u, t1);
    constexpr double h = 1e-3;
    const auto along = [&](glm::dvec3 t, double a) { return wave(std::cos(a) * u + std::sin(a) * t).value; };
    const double f = wave(u).value;
    const double laplacian =
        (along(t1, h) + along(t1, -h) + along(t2, h) + along(t2, -h) - 4.0 * f) / (h * h);
    EXPECT_NEAR(laplacian, -132.0 * f, 1e-3 * 132.0 * wave.rms());
  }
}

TEST(SphericalWave, HasTheStatedRootMeanSquareOverSeeds) {
  // The mean square over the sphere and over seeds is (2l + 1) / (4 pi) / 3.
  double sum = 0.0;
  int samples = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const SphericalWave wave(9, seed);
    for (int i = 0; i < 400; ++i, ++samples) sum += std::pow(wave(spiral_point(i, 400)).value, 2);
  }
  EXPECT_NEAR(std::sqrt(sum / samples), SphericalWave(9, 1).rms(), 0.1 * SphericalWave(9, 1).rms());
}

TEST(SphericalWave, SameSeedSameWaveOtherSeedOtherWave) {
  const glm::dvec3 u = glm::normalize(glm::dvec3(0.2, -0.4, 0.9));
  EXPECT_EQ(SphericalWave(13, 5)(u).value, SphericalWave(13, 5)(u).value);
  EXPECT_NE(SphericalWave(13, 5)(u).value, SphericalWave(13, 6)(u).value);
}

TEST(SphericalWave, RejectsDegreesItCannotEvaluate) {
  EXPECT_THROW(SphericalWave(0, 1), Error);
  EXPECT_THROW(SphericalWave(65, 1), Error);
}

}  // namespace
}  // namespace palpate::detail
