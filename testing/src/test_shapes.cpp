#include "palpate/testing/test_shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>

#include "palpate/core/shapes.hpp"

namespace palpate::testing {

Scene scene_of(const std::string& name, Mesh mesh) {
  Scene scene;
  scene.objects.push_back({name, std::move(mesh), glm::mat4(1.0f), {}, {}});
  return scene;
}

Mesh make_hollow_box(float outer_mm, float inner_mm) {
  Mesh mesh = make_box(glm::vec3(outer_mm));
  Mesh cavity = make_box(glm::vec3(inner_mm));
  for (std::size_t t = 0; t < cavity.indices.size(); t += 3)
    std::swap(cavity.indices[t + 1], cavity.indices[t + 2]);
  for (glm::vec3& n : cavity.normals) n = -n;
  append_mesh(mesh, cavity);
  return mesh;
}

Mesh make_comb(int teeth, float tooth_width_mm, float gap_mm, float tooth_height_mm, float base_height_mm,
               float depth_mm) {
  const float pitch = tooth_width_mm + gap_mm;
  const float width = float(teeth) * tooth_width_mm + float(teeth - 1) * gap_mm;
  const float top = base_height_mm + tooth_height_mm;
  std::vector<float> xs;  // every tooth side
  for (int k = 0; k < teeth; ++k) xs.insert(xs.end(), {float(k) * pitch, float(k) * pitch + tooth_width_mm});
  // The outline, counter-clockwise seen from +z, with a vertex wherever a cap triangle has one.
  std::vector<glm::vec2> outline;
  for (float x : xs) outline.push_back({x, 0.0f});
  for (int k = teeth - 1; k >= 0; --k) {
    const float left = float(k) * pitch, right = left + tooth_width_mm;
    outline.insert(outline.end(),
                   {{right, base_height_mm}, {right, top}, {left, top}, {left, base_height_mm}});
  }
  // Cap quads: the base cut at every tooth side, then the teeth.
  std::vector<std::array<glm::vec2, 4>> quads;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    quads.push_back(
        {{{xs[i], 0.0f}, {xs[i + 1], 0.0f}, {xs[i + 1], base_height_mm}, {xs[i], base_height_mm}}});
  }
  for (int k = 0; k < teeth; ++k) {
    const float left = float(k) * pitch, right = left + tooth_width_mm;
    quads.push_back({{{left, base_height_mm}, {right, base_height_mm}, {right, top}, {left, top}}});
  }
  Mesh mesh;
  std::map<std::tuple<float, float, float>, std::uint32_t> index;
  const auto vertex = [&](glm::vec2 p, float z) {
    const auto key = std::make_tuple(p.x - 0.5f * width, p.y, z - 0.5f * depth_mm);
    const auto [it, added] = index.emplace(key, std::uint32_t(mesh.positions_mm.size()));
    if (added) mesh.positions_mm.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key)});
    return it->second;
  };
  const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
  };
  for (const auto& q : quads) {
    quad(vertex(q[0], depth_mm), vertex(q[1], depth_mm), vertex(q[2], depth_mm),
         vertex(q[3], depth_mm));                                                          // +z cap
    quad(vertex(q[0], 0.0f), vertex(q[3], 0.0f), vertex(q[2], 0.0f), vertex(q[1], 0.0f));  // -z cap
  }
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const glm::vec2 a = outline[i], b = outline[(i + 1) % outline.size()];
    quad(vertex(a, 0.0f), vertex(b, 0.0f), vertex(b, depth_mm), vertex(a, depth_mm));
  }
  compute_vertex_normals(mesh);
  return mesh;
}

Mesh make_torus(float major_mm, float minor_mm, int segments, int sides) {
  Mesh mesh;
  const float two_pi = 6.28318530718f;
  for (int i = 0; i < segments; ++i) {
    const float u = two_pi * float(i) / float(segments);
    for (int j = 0; j < sides; ++j) {
      const float v = two_pi * float(j) / float(sides);
      const glm::vec3 ring(std::cos(u), std::sin(u), 0.0f);
      mesh.positions_mm.push_back(ring * (major_mm + minor_mm * std::cos(v)) +
                                  glm::vec3(0, 0, minor_mm * std::sin(v)));
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t((i % segments) * sides + (j % sides)); };
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j) {
      mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  compute_vertex_normals(mesh);
  return mesh;
}

void add_sheet(Mesh& mesh, float z, std::size_t cells, bool facing_up) {
  Mesh sheet = make_grid(60.0f, cells);
  for (glm::vec3& p : sheet.positions_mm) p.z = z;
  if (!facing_up) {
    for (glm::vec3& n : sheet.normals) n = -n;
    for (std::size_t i = 0; i < sheet.indices.size(); i += 3)
      std::swap(sheet.indices[i + 1], sheet.indices[i + 2]);
  }
  const std::uint32_t first = std::uint32_t(mesh.vertex_count());
  mesh.positions_mm.insert(mesh.positions_mm.end(), sheet.positions_mm.begin(), sheet.positions_mm.end());
  mesh.normals.insert(mesh.normals.end(), sheet.normals.begin(), sheet.normals.end());
  for (const std::uint32_t i : sheet.indices) mesh.indices.push_back(first + i);
}

Mesh split_flat(const Mesh& mesh) {
  Mesh flat;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions_mm[mesh.indices[t]], b = mesh.positions_mm[mesh.indices[t + 1]],
                    c = mesh.positions_mm[mesh.indices[t + 2]];
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const glm::vec3& p : {a, b, c}) {
      flat.indices.push_back(std::uint32_t(flat.positions_mm.size()));
      flat.positions_mm.push_back(p);
      flat.normals.push_back(n);
    }
  }
  return flat;
}

Mesh make_folded_sheet() {
  Mesh mesh = make_grid(100.0f, 100);
  constexpr float bend_start = 40.0f, radius = 3.0f;
  const float half_turn = std::numbers::pi_v<float> * radius;
  for (glm::vec3& p : mesh.positions_mm) {
    const float s = p.x + 50.0f;  // arc length along the sheet, 0..100
    if (s <= bend_start) {
      p = {s, p.y, 0.0f};
    } else if (s <= bend_start + half_turn) {
      const float angle = (s - bend_start) / radius;
      p = {bend_start + radius * std::sin(angle), p.y, radius - radius * std::cos(angle)};
    } else {
      p = {bend_start - (s - bend_start - half_turn), p.y, 2.0f * radius};
    }
  }
  compute_vertex_normals(mesh);
  return mesh;
}

}  // namespace palpate::testing
