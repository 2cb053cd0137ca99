#include "core/spherical_wave.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "palpate/core/error.hpp"

namespace palpate::detail {
namespace {

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Uniform in [-1, 1): variance 1/3.
double uniform_symmetric(std::uint64_t& state) {
  return double(splitmix64(state) >> 11) * 0x1.0p-52 - 1.0;
}

}  // namespace

SphericalWave::SphericalWave(int degree, std::uint64_t seed) : degree_(degree) {
  if (degree < 1 || degree > 64) {
    throw Error("SphericalWave: degree must be in [1, 64], got " + std::to_string(degree));
  }
  const double l = degree;
  wavenumber_ = std::sqrt(l * (l + 1.0));
  // Orthonormal real harmonics with independent coefficients of variance 1/3: by the addition theorem
  // the value's variance is (2l + 1) / (4 pi) / 3 everywhere.
  rms_ = std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) / 3.0);
  cos_coefficient_.resize(std::size_t(degree) + 1);
  sin_coefficient_.resize(std::size_t(degree) + 1);
  std::uint64_t state = seed;
  for (int m = 0; m <= degree; ++m) {
    // Y_lm = N_lm P_l^m(cos theta) {cos, sin}(m phi), N_lm^2 = (2 - [m = 0]) (2l + 1) / (4 pi) (l - m)! / (l
    // + m)!. operator() evaluates P_l^m / (2m - 1)!!, so that factor joins the coefficient too.
    double ratio = 1.0;  // (l - m)! / (l + m)!
    for (int j = degree - m + 1; j <= degree + m; ++j) ratio /= double(j);
    double double_factorial = 1.0;  // (2m - 1)!!
    for (int j = 2 * m - 1; j > 1; j -= 2) double_factorial *= double(j);
    const double norm = std::sqrt((m == 0 ? 1.0 : 2.0) * (2.0 * l + 1.0) / (4.0 * std::numbers::pi) * ratio) *
                        double_factorial;
    cos_coefficient_[std::size_t(m)] = norm * uniform_symmetric(state);
    sin_coefficient_[std::size_t(m)] = m == 0 ? 0.0 : norm * uniform_symmetric(state);
  }
  for (int k = 0; k < degree; ++k) {
    for (int m = 0; m <= k; ++m) {
      z_factor_.push_back(double(2 * k + 1) / double(k - m + 1));
      previous_factor_.push_back(double(k + m) / double(k - m + 1));
    }
  }
}

SphericalWave::Sample SphericalWave::operator()(glm::dvec3 u) const noexcept {
  // On the unit sphere P_l^m(z) {cos, sin}(m phi) = Q_l^m(z) {Re, Im}(x + i y)^m, where Q follows the
  // Legendre recurrence (k - m + 1) Q_{k+1} = (2k + 1) z Q_k - (k + m) Q_{k-1}, with Q_m = 1 here. That
  // is a polynomial in x, y, z; its gradient, less the radial part, is the gradient on the sphere.
  // All orders m step through k together: the steps are independent, not one long chain.
  constexpr int max_degree = 64;
  double q[max_degree + 1], q_z[max_degree + 1], qp[max_degree + 1], qp_z[max_degree + 1];
  const int l = std::min(degree_, max_degree);
  std::size_t factor = 0;
  for (int k = 0; k < l; ++k) {
    q[k] = 1.0, q_z[k] = 0.0, qp[k] = 0.0, qp_z[k] = 0.0;  // order k starts at Q_k^k
    for (int m = 0; m <= k; ++m, ++factor) {
      const double a = z_factor_[factor], b = previous_factor_[factor];
      const double next = a * u.z * q[m] - b * qp[m];
      const double next_z = a * (q[m] + u.z * q_z[m]) - b * qp_z[m];
      qp[m] = q[m], qp_z[m] = q_z[m];
      q[m] = next, q_z[m] = next_z;
    }
  }
  q[l] = 1.0, q_z[l] = 0.0;

  double value = 0.0;
  glm::dvec3 grad(0.0);
  double re = 1.0, im = 0.0;            // (x + i y)^m
  double re_prev = 0.0, im_prev = 0.0;  // (x + i y)^(m - 1)
  for (int m = 0; m <= l; ++m) {
    if (m > 0) {
      re_prev = re, im_prev = im;
      re = re_prev * u.x - im_prev * u.y;
      im = re_prev * u.y + im_prev * u.x;
    }
    const double cm = cos_coefficient_[std::size_t(m)], sm = sin_coefficient_[std::size_t(m)];
    const double angular = cm * re + sm * im;
    // d/dx (x + i y)^m = m (x + i y)^(m-1); d/dy = i m (x + i y)^(m-1).
    value += q[m] * angular;
    grad.x += q[m] * double(m) * (cm * re_prev + sm * im_prev);
    grad.y += q[m] * double(m) * (sm * re_prev - cm * im_prev);
    grad.z += q_z[m] * angular;
  }
  return {value, grad - glm::dot(grad, u) * u};
}

}  // namespace palpate::detail
