#include "core/weld.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <numbers>

namespace palpate::detail {
namespace {

// Bit pattern of a float with -0 folded into +0, so that equal values weld.
std::uint32_t bits(float v) noexcept {
  return std::bit_cast<std::uint32_t>(v == 0.0f ? 0.0f : v);
}

using PositionKey = std::array<std::uint32_t, 3>;
PositionKey position_key(glm::vec3 p) noexcept {
  return {bits(p.x), bits(p.y), bits(p.z)};
}

std::uint64_t hash(const PositionKey& key) noexcept {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (std::uint32_t word : key) h = (h ^ word) * 0xff51afd7ed558ccdull;
  return h ^ (h >> 32);
}

// Ids of distinct positions, in order of first appearance; returns the id of each input position.
// An open-addressing table: a million lookups a load, where std::unordered_map's nodes cost.
std::vector<std::uint32_t> weld_ids(const std::vector<glm::vec3>& positions,
                                    std::vector<glm::vec3>& distinct) {
  constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::size_t capacity = 16;
  while (capacity < positions.size() * 2) capacity *= 2;
  std::vector<std::uint32_t> slots(capacity, kEmpty);
  std::vector<PositionKey> keys;
  std::vector<std::uint32_t> id_of(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const PositionKey key = position_key(positions[i]);
    std::size_t slot = hash(key) & (capacity - 1);
    while (slots[slot] != kEmpty && keys[slots[slot]] != key) slot = (slot + 1) & (capacity - 1);
    if (slots[slot] == kEmpty) {
      slots[slot] = static_cast<std::uint32_t>(keys.size());
      keys.push_back(key);
      distinct.push_back(positions[i]);
    }
    id_of[i] = slots[slot];
  }
  return id_of;
}

glm::vec3 unit_or_zero(glm::vec3 v) noexcept {
  const float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : glm::vec3(0.0f);
}

// Corner normals from the faces around each position, within the crease angle of the corner's face.
std::vector<glm::vec3> crease_normals(const std::vector<glm::vec3>& positions,
                                      const std::vector<std::uint32_t>& position_id,
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
  for (std::size_t c = 0; c < corners; ++c)
    around[fill[position_id[c]]++] = static_cast<std::uint32_t>(c / 3);

  // A small tolerance keeps the triangles of one planar polygon together at creaseAngle 0.
  const float min_cos =
      crease_angle_rad >= std::numbers::pi_v<float> ? -2.0f : std::cos(crease_angle_rad) - 1e-5f;
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
  const std::size_t corners = soup.positions_mm.size() / 3 * 3;
  std::vector<glm::vec3> distinct;
  const std::vector<std::uint32_t> position_id = weld_ids(soup.positions_mm, distinct);

  std::vector<glm::vec3> normals;
  if (soup.normals.empty()) {
    normals = crease_normals(soup.positions_mm, position_id, distinct.size(), crease_angle_rad);
  } else {
    normals.resize(corners);
    for (std::size_t c = 0; c < corners; ++c) {
      normals[c] = unit_or_zero(soup.normals[c]);
      if (normals[c] == glm::vec3(0.0f)) {  // a zero normal in the file: use the face's own
        const std::size_t t = c / 3 * 3;
        normals[c] = unit_or_zero(glm::cross(soup.positions_mm[t + 1] - soup.positions_mm[t],
                                             soup.positions_mm[t + 2] - soup.positions_mm[t]));
      }
    }
  }
  const bool colored = !soup.colors.empty();

  // The vertices of each position form a short list (one per normal and colour met there).
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> first_vertex(distinct.size(), kNone), next_vertex;
  Mesh mesh;
  mesh.indices.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const glm::vec3 n = normals[c];
    const glm::vec3 color = colored ? soup.colors[c] : glm::vec3(0.0f);
    std::uint32_t v = first_vertex[position_id[c]];
    while (v != kNone && !(position_key(mesh.normals[v]) == position_key(n) &&
                           (!colored || position_key(mesh.colors[v]) == position_key(color)))) {
      v = next_vertex[v];
    }
    if (v == kNone) {
      v = static_cast<std::uint32_t>(mesh.positions_mm.size());
      mesh.positions_mm.push_back(distinct[position_id[c]]);
      mesh.normals.push_back(n);
      if (colored) mesh.colors.push_back(color);
      next_vertex.push_back(first_vertex[position_id[c]]);
      first_vertex[position_id[c]] = v;
    }
    mesh.indices.push_back(v);
  }
  return mesh;
}

void weld_identical(Mesh& mesh) {
  std::vector<glm::vec3> distinct;
  const std::vector<std::uint32_t> position_id = weld_ids(mesh.positions_mm, distinct);
  if (distinct.size() == mesh.positions_mm.size()) return;
  const bool has_normals = mesh.normals.size() == mesh.positions_mm.size();
  const bool colored = !mesh.colors.empty();
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> first_vertex(distinct.size(), kNone), next_vertex,
      merged(mesh.positions_mm.size());
  Mesh out;
  for (std::size_t i = 0; i < mesh.positions_mm.size(); ++i) {
    const std::uint32_t id = position_id[i];
    std::uint32_t v = first_vertex[id];
    while (v != kNone && !((!has_normals || position_key(out.normals[v]) == position_key(mesh.normals[i])) &&
                           (!colored || position_key(out.colors[v]) == position_key(mesh.colors[i])))) {
      v = next_vertex[v];
    }
    if (v == kNone) {
      v = static_cast<std::uint32_t>(out.positions_mm.size());
      out.positions_mm.push_back(mesh.positions_mm[i]);
      if (has_normals) out.normals.push_back(mesh.normals[i]);
      if (colored) out.colors.push_back(mesh.colors[i]);
      next_vertex.push_back(first_vertex[id]);
      first_vertex[id] = v;
    }
    merged[i] = v;
  }
  for (std::uint32_t& index : mesh.indices) index = merged[index];
  mesh.positions_mm = std::move(out.positions_mm);
  mesh.normals = std::move(out.normals);
  mesh.colors = std::move(out.colors);
}

void weld_positions(Mesh& mesh) {
  std::vector<glm::vec3> distinct;
  const std::vector<std::uint32_t> id_of = weld_ids(mesh.positions_mm, distinct);
  if (distinct.size() == mesh.positions_mm.size() && !mesh.normals.empty()) return;  // nothing to merge

  const bool had_normals = mesh.normals.size() == mesh.positions_mm.size();
  std::vector<glm::vec3> normals(distinct.size()), colors;
  std::vector<bool> seen(distinct.size(), false), agree(distinct.size(), had_normals);
  if (!mesh.colors.empty()) colors.resize(distinct.size());
  for (std::size_t v = 0; v < mesh.positions_mm.size(); ++v) {
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
  mesh.positions_mm = std::move(distinct);
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
