#include "surface_reference.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "palpate/core/error.hpp"

namespace palpate::cli {

double BumpySphereReference::radius_at(glm::dvec3 u) const noexcept {
  return radius_mm_ + bump_mm_ * std::sin(15.0 * u.x) * std::sin(15.0 * u.y) * std::sin(15.0 * u.z + 0.7);
}

double BumpySphereReference::implicit(glm::dvec3 p) const noexcept {
  const double r = glm::length(p);
  return radius_at(p / r) - r;
}

glm::dvec3 BumpySphereReference::gradient(glm::dvec3 p) const noexcept {
  const double h = 1e-4;
  glm::dvec3 g;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 step(0.0);
    step[axis] = h;
    g[axis] = (implicit(p + step) - implicit(p - step)) / (2.0 * h);
  }
  return g;
}

double BumpySphereReference::depth_mm(glm::vec3 p) const {
  return implicit(glm::dvec3(p)) / glm::length(gradient(glm::dvec3(p)));
}

bool SurfaceReference::pushes_inward(glm::vec3 p, glm::vec3 force) const {
  const float length = glm::length(force);
  if (length == 0.0f) return false;
  return depth_mm(p + force * (0.05f / length)) > depth_mm(p);
}

void BumpySphereReference::verify(const Mesh& mesh) const {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 v(mesh.positions[i]);
    const double off = std::abs(glm::length(v) - radius_at(glm::normalize(v)));
    if (!(off <= 1e-3)) {
      throw Error("bench haptics: vertex " + std::to_string(i) + " of the bumpy sphere is " +
                  std::to_string(off) +
                  " mm off the reference surface: make_bumpy_sphere changed, update BumpySphereReference");
    }
  }
}

}  // namespace palpate::cli
