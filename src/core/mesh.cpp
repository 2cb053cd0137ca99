#include "palpate/core/mesh.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/finite.hpp"

namespace palpate {

Bounds bounds(const Mesh& mesh) noexcept {
  if (mesh.positions_mm.empty()) return {};
  Bounds b{mesh.positions_mm.front(), mesh.positions_mm.front()};
  for (const glm::vec3& p : mesh.positions_mm) {
    b.min_mm = glm::min(b.min_mm, p);
    b.max_mm = glm::max(b.max_mm, p);
  }
  return b;
}

void compute_vertex_normals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions_mm.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    // The cross product's length is twice the area: summing it weights each face by area.
    const glm::vec3 face =
        glm::cross(mesh.positions_mm[b] - mesh.positions_mm[a], mesh.positions_mm[c] - mesh.positions_mm[a]);
    mesh.normals[a] += face;
    mesh.normals[b] += face;
    mesh.normals[c] += face;
  }
  for (glm::vec3& n : mesh.normals) {
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
}

void append_mesh(Mesh& into, const Mesh& part, glm::vec3 fill_color) {
  const auto offset = static_cast<std::uint32_t>(into.positions_mm.size());
  const bool colored = !into.colors.empty() || !part.colors.empty();
  if (colored && into.colors.empty()) into.colors.assign(into.positions_mm.size(), fill_color);
  into.positions_mm.insert(into.positions_mm.end(), part.positions_mm.begin(), part.positions_mm.end());
  into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
  if (!into.directions.empty() || !part.directions.empty()) {  // the side without: its normals
    if (into.directions.empty())
      into.directions.assign(into.normals.begin(), into.normals.end() - part.normals.size());
    const std::vector<glm::vec3>& more = part.directions.empty() ? part.normals : part.directions;
    into.directions.insert(into.directions.end(), more.begin(), more.end());
  }
  if (colored) {
    if (part.colors.empty()) {
      into.colors.insert(into.colors.end(), part.positions_mm.size(), fill_color);
    } else {
      into.colors.insert(into.colors.end(), part.colors.begin(), part.colors.end());
    }
  }
  into.indices.reserve(into.indices.size() + part.indices.size());
  for (std::uint32_t i : part.indices) into.indices.push_back(i + offset);
}

namespace {}  // namespace

void validate_mesh(const Mesh& mesh, const std::string& what) {
  if (mesh.indices.size() % 3 != 0) {
    throw Error(what + ": index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  }
  if (mesh.normals.size() != mesh.positions_mm.size()) {
    throw Error(what + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                std::to_string(mesh.positions_mm.size()) + " positions");
  }
  if (!mesh.directions.empty() && mesh.directions.size() != mesh.positions_mm.size()) {
    throw Error(what + ": " + std::to_string(mesh.directions.size()) + " directions for " +
                std::to_string(mesh.positions_mm.size()) + " positions");
  }
  if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions_mm.size()) {
    throw Error(what + ": " + std::to_string(mesh.colors.size()) + " colors for " +
                std::to_string(mesh.positions_mm.size()) + " positions");
  }
  for (std::size_t i = 0; i < mesh.positions_mm.size(); ++i) {
    if (!is_finite(mesh.positions_mm[i])) {
      throw Error(what + ": vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or Inf)");
    }
    if (!is_finite(mesh.normals[i])) throw Error(what + ": normal " + std::to_string(i) + " is not finite");
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.positions_mm.size()) {
      throw Error(what + ": triangle " + std::to_string(i / 3) + " uses vertex " +
                  std::to_string(mesh.indices[i]) + " but there are only " +
                  std::to_string(mesh.positions_mm.size()));
    }
  }
}

}  // namespace palpate
