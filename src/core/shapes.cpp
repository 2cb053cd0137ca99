#include "palpate/core/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "palpate/core/error.hpp"

namespace palpate {
namespace {

constexpr float pi = std::numbers::pi_v<float>;

// Vertex counts per latitude ring, summing exactly to `total`, proportional to sin(latitude).
std::vector<std::size_t> ring_sizes(std::size_t total) {
  // With rings spaced pi/(R+1) apart and ring i holding about 2 (R+1) sin(theta_i) vertices, the
  // triangles are near equilateral and the rings hold 4 (R+1)^2 / pi vertices in all.
  const auto rings = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::lround(std::sqrt(pi * static_cast<float>(total) / 4.0f))) - 1);
  std::vector<double> weight(rings);
  for (std::size_t i = 0; i < rings; ++i)
    weight[i] = std::sin(std::numbers::pi * double(i + 1) / double(rings + 1));
  const double weight_sum = std::accumulate(weight.begin(), weight.end(), 0.0);
  std::vector<std::size_t> size(rings);
  std::vector<double> remainder(rings);
  std::size_t assigned = 0;
  for (std::size_t i = 0; i < rings; ++i) {
    const double exact = double(total) * weight[i] / weight_sum;
    size[i] = static_cast<std::size_t>(exact);
    remainder[i] = exact - double(size[i]);
    assigned += size[i];
  }
  // Hand the rounding leftovers to the rings that lost the most.
  std::vector<std::size_t> order(rings);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return remainder[a] > remainder[b]; });
  for (std::size_t k = 0; assigned < total; k = (k + 1) % rings, ++assigned) ++size[order[k]];
  return size;
}

}  // namespace

Mesh make_sphere(float radius_mm, std::size_t vertices) {
  if (vertices < 5) throw Error("make_sphere: need at least 5 vertices, got " + std::to_string(vertices));
  const std::vector<std::size_t> sizes = ring_sizes(vertices - 2);
  if (std::any_of(sizes.begin(), sizes.end(), [](std::size_t n) { return n < 3; })) {
    throw Error("make_sphere: " + std::to_string(vertices) +
                " vertices are too few for closed latitude rings");
  }
  const std::size_t rings = sizes.size();
  Mesh mesh;
  mesh.positions_mm.reserve(vertices);
  std::vector<std::uint32_t> first(rings);
  std::vector<float> phase(rings);
  mesh.positions_mm.push_back({0.0f, 0.0f, radius_mm});  // north pole, index 0
  for (std::size_t r = 0; r < rings; ++r) {
    const float theta = pi * float(r + 1) / float(rings + 1);
    first[r] = static_cast<std::uint32_t>(mesh.positions_mm.size());
    // Half a step of stagger between neighbouring rings avoids long slivers where counts match.
    phase[r] = (r % 2 == 0 ? 0.0f : 0.5f) * 2.0f * pi / float(sizes[r]);
    for (std::size_t k = 0; k < sizes[r]; ++k) {
      const float phi = phase[r] + 2.0f * pi * float(k) / float(sizes[r]);
      mesh.positions_mm.push_back(radius_mm * glm::vec3(std::sin(theta) * std::cos(phi),
                                                        std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  const auto south = static_cast<std::uint32_t>(mesh.positions_mm.size());
  mesh.positions_mm.push_back({0.0f, 0.0f, -radius_mm});

  auto& tri = mesh.indices;
  tri.reserve(6 * (vertices - 2));
  // Caps: counter-clockwise seen from outside.
  for (std::size_t k = 0; k < sizes[0]; ++k) {
    tri.insert(tri.end(), {0u, first[0] + std::uint32_t(k), first[0] + std::uint32_t((k + 1) % sizes[0])});
  }
  const std::size_t last = rings - 1;
  for (std::size_t k = 0; k < sizes[last]; ++k) {
    tri.insert(tri.end(),
               {south, first[last] + std::uint32_t((k + 1) % sizes[last]), first[last] + std::uint32_t(k)});
  }
  // Stitch ring r (upper) to ring r+1 (lower) in order of azimuth: each step advances one ring.
  for (std::size_t r = 0; r + 1 < rings; ++r) {
    const std::size_t nu = sizes[r], nl = sizes[r + 1];
    const auto angle = [&](std::size_t ring, std::size_t k) {
      return phase[ring] + 2.0f * pi * float(k) / float(sizes[ring]);
    };
    std::size_t iu = 0, il = 0;
    // Start the lower ring at the vertex closest in angle to the upper ring's first vertex.
    const std::size_t offset = phase[r + 1] > phase[r] + 1e-6f ? nl - 1 : 0;
    while (iu < nu || il < nl) {
      const std::uint32_t u0 = first[r] + std::uint32_t(iu % nu),
                          u1 = first[r] + std::uint32_t((iu + 1) % nu);
      const std::uint32_t l0 = first[r + 1] + std::uint32_t((il + offset) % nl);
      const std::uint32_t l1 = first[r + 1] + std::uint32_t((il + offset + 1) % nl);
      const float next_upper = angle(r, iu + 1);
      const float next_lower = angle(r + 1, il + offset + 1) - (offset ? 2.0f * pi : 0.0f);
      if (il == nl || (iu < nu && next_upper <= next_lower)) {
        tri.insert(tri.end(), {u0, l0, u1});
        ++iu;
      } else {
        tri.insert(tri.end(), {u0, l0, l1});
        ++il;
      }
    }
  }
  compute_vertex_normals(mesh);
  return mesh;
}

Mesh make_bumpy_sphere(float radius_mm, float bump_mm, std::size_t triangles) {
  const std::size_t even = std::max<std::size_t>(6, (triangles + 1) / 2 * 2);
  Mesh mesh = make_sphere(1.0f, even / 2 + 2);
  for (glm::vec3& p : mesh.positions_mm) {
    // A product of sines in the direction's coordinates: smooth, in [-1, 1], bumps ~12 degrees apart.
    const float k = 15.0f;
    const float bump = std::sin(k * p.x) * std::sin(k * p.y) * std::sin(k * p.z + 0.7f);
    p *= radius_mm + bump_mm * bump;
  }
  compute_vertex_normals(mesh);
  return mesh;
}

Mesh make_box(glm::vec3 size_mm) {
  const glm::vec3 h = size_mm * 0.5f;
  Mesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.positions_mm.push_back({i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z});
  mesh.indices = {0, 2, 1, 1, 2, 3,   // -z
                  4, 5, 6, 5, 7, 6,   // +z
                  0, 1, 4, 1, 5, 4,   // -y
                  2, 6, 3, 3, 6, 7,   // +y
                  0, 4, 2, 2, 4, 6,   // -x
                  1, 3, 5, 3, 7, 5};  // +x
  compute_vertex_normals(mesh);
  return mesh;
}

Mesh make_grid(float size_mm, std::size_t cells) {
  Mesh mesh;
  const std::size_t n = cells + 1;
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < n; ++i) {
      mesh.positions_mm.push_back(
          {size_mm * (float(i) / float(cells) - 0.5f), size_mm * (float(j) / float(cells) - 0.5f), 0.0f});
      mesh.normals.push_back({0.0f, 0.0f, 1.0f});
    }
  }
  for (std::size_t j = 0; j < cells; ++j) {
    for (std::size_t i = 0; i < cells; ++i) {
      const auto a = std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
  return mesh;
}

}  // namespace palpate
