#include "core/weld.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <numbers>
#include <unordered_map>

namespace palpate::detail {
namespace {

// Bit pattern of a float with -0 folded into +0, so that equal values weld.
std::uint32_t bits(float v) noexcept { return std::bit_cast<std::uint32_t>(v == 0.0f ? 0.0f : v); }

template <std::size_t N>
struct KeyHash {
  std::size_t operator()(const std::array<std::uint32_t, N>& key) const noexcept {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
    for (std::uint32_t word : key) h = (h ^ word) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

using PositionKey = std::array<std::uint32_t, 3>;
PositionKey position_key(glm::vec3 p) noexcept { return {bits(p.x), bits(p.y), bits(p.z)}; }

// Ids of distinct positions, in order of first appearance; returns the id of each input position.
std::vector<std::uint32_t> weld_ids(const std::vector<glm::vec3>& positions, std::vector<glm::vec3>& distinct) {
  std::unordered_map<PositionKey, std::uint32_t, KeyHash<3>> ids;
  ids.reserve(positions.size());
  std::vector<std::uint32_t> id_of(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto [it, inserted] = ids.try_emplace(position_key(positions[i]), static_cast<std::uint32_t>(distinct.size()));
    if (inserted) distinct.push_back(positions[i]);
    id_of[i] = it->second;
  }
  return id_of;
}

glm::vec3 unit_or_zero(glm::vec3 v) noexcept {
  const float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : glm::vec3(0.0f);
}

// Corner normals from the faces around each position, within the crease angle of the corner's face.
std::vector<glm::vec3> crease_normals(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& position_id,
                                      std::size_t position_count, float crease_angle_rad) {
  const std::size_t corners = positions.size();
  const std::size_t triangles = corners / 3;
  std::vector<glm::vec3> face(triangles), face_unit(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::vec3 a = positions[3 * t], b = positions[3 * t + 1], c = positions[3 * t + 2];
    face[t] = glm::cross(b - a, c - a);  // length = twice the area: the area weight
    face_unit[t] = unit_or_zero(face[t]);
  }
  // Triangles around each position, in a fixed order so that equal sets give bitwise equal sums.
  std::vector<std::uint32_t> first(position_count + 1, 0);
  for (std::uint32_t id : position_id) ++first[id + 1];
  for (std::size_t v = 0; v < position_count; ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> around(corners);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t c = 0; c < corners; ++c) around[fill[position_id[c]]++] = static_cast<std::uint32_t>(c / 3);

  // A small tolerance keeps the triangles of one planar polygon together at creaseAngle 0.
  const float min_cos = crease_angle_rad >= std::numbers::pi_v<float> ? -2.0f : std::cos(crease_angle_rad) - 1e-5f;
  std::vector<glm::vec3> normals(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const std::size_t t = c / 3;
    glm::vec3 sum(0.0f);
    for (std::uint32_t i = first[position_id[c]]; i < first[position_id[c] + 1]; ++i) {
      const std::uint32_t other = around[i];
      if (other == t || glm::dot(face_unit[t], face_unit[other]) >= min_cos) sum += face[other];
    }
    glm::vec3 n = unit_or_zero(sum);
    if (n == glm::vec3(0.0f)) n = face_unit[t];
    normals[c] = n == glm::vec3(0.0f) ? glm::vec3(0.0f, 0.0f, 1.0f) : n;
  }
  return normals;
}

}  // namespace

Mesh mesh_from_soup(const TriangleSoup& soup, float crease_angle_rad) {
  const std::size_t corners = soup.positions.size() / 3 * 3;
  std::vector<glm::vec3> distinct;
  const std::vector<std::uint32_t> position_id = weld_ids(soup.positions, distinct);

  std::vector<glm::vec3> normals;
  if (soup.normals.empty()) {
    normals = crease_normals(soup.positions, position_id, distinct.size(), crease_angle_rad);
  } else {
    normals.resize(corners);
    for (std::size_t c = 0; c < corners; ++c) {
      normals[c] = unit_or_zero(soup.normals[c]);
      if (normals[c] == glm::vec3(0.0f)) {  // a zero normal in the file: use the face's own
        const std::size_t t = c / 3 * 3;
        normals[c] = unit_or_zero(
            glm::cross(soup.positions[t + 1] - soup.positions[t], soup.positions[t + 2] - soup.positions[t]));
      }
    }
  }
  const bool colored = !soup.colors.empty();

  using VertexKey = std::array<std::uint32_t, 7>;
  std::unordered_map<VertexKey, std::uint32_t, KeyHash<7>> vertex_of;
  vertex_of.reserve(distinct.size() * 2);
  Mesh mesh;
  mesh.indices.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const glm::vec3 n = normals[c];
    const glm::vec3 color = colored ? soup.colors[c] : glm::vec3(0.0f);
    const VertexKey key{position_id[c], bits(n.x), bits(n.y), bits(n.z), bits(color.r), bits(color.g), bits(color.b)};
    const auto [it, inserted] = vertex_of.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
    if (inserted) {
      mesh.positions.push_back(distinct[position_id[c]]);
      mesh.normals.push_back(n);
      if (colored) mesh.colors.push_back(color);
    }
    mesh.indices.push_back(it->second);
  }
  return mesh;
}

void weld_positions(Mesh& mesh) {
  std::vector<glm::vec3> distinct;
  const std::vector<std::uint32_t> id_of = weld_ids(mesh.positions, distinct);
  if (distinct.size() == mesh.positions.size() && !mesh.normals.empty()) return;  // nothing to merge

  const bool had_normals = mesh.normals.size() == mesh.positions.size();
  std::vector<glm::vec3> normals(distinct.size()), colors;
  std::vector<bool> seen(distinct.size(), false), agree(distinct.size(), had_normals);
  if (!mesh.colors.empty()) colors.resize(distinct.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const std::uint32_t id = id_of[v];
    if (!seen[id]) {
      seen[id] = true;
      if (had_normals) normals[id] = mesh.normals[v];
      if (!colors.empty()) colors[id] = mesh.colors[v];
    } else if (had_normals && agree[id] && position_key(normals[id]) != position_key(mesh.normals[v])) {
      agree[id] = false;
    }
  }
  for (std::uint32_t& i : mesh.indices) i = id_of[i];
  mesh.positions = std::move(distinct);
  mesh.colors = std::move(colors);
  const bool all_agree = std::all_of(agree.begin(), agree.end(), [](bool a) { return a; });
  if (!all_agree) {
    compute_vertex_normals(mesh);  // area-weighted over the welded triangles
    for (std::size_t v = 0; v < normals.size(); ++v) {
      if (agree[v]) mesh.normals[v] = normals[v];
    }
  } else {
    mesh.normals = std::move(normals);
  }
}

}  // namespace palpate::detail
