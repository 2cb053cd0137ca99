// The occlusion proxy on the CPU: a closed convex mesh that contains every point within the margin and
// the pad of the object, checked face by face against the object's own vertices (no GL).
#include "gl/occlusion_proxy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/vec3.hpp>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate::gl {
namespace {

std::vector<glm::vec3> transformed(const Mesh& mesh, const glm::mat4& transform) {
  std::vector<glm::vec3> world;
  for (const glm::vec3& p : mesh.positions_mm) world.emplace_back(transform * glm::vec4(p, 1.0f));
  return world;
}

// Every directed edge of the proxy appears once and its reverse once: closed, consistently wound.
void expect_closed(const OcclusionProxy& proxy) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < proxy.indices.size(); t += 3) {
    for (std::size_t k = 0; k < 3; ++k) ++edges[{proxy.indices[t + k], proxy.indices[t + (k + 1) % 3]}];
  }
  std::size_t unpaired = 0;
  for (const auto& [edge, count] : edges)
    unpaired += count != 1 || !edges.contains({edge.second, edge.first});
  EXPECT_EQ(unpaired, 0u);
}

// Padded by `pad`: every face turns outward, has every proxy vertex behind it (convex), and lies at
// least `clearance` beyond the farthest point of the object in its direction, so that it holds every
// point within `clearance` of the object: for a convex polytope, the face planes decide. Slivers (the
// triangulation of collinear hull points) are skipped: their planes are lost in the rounding of their
// corners, and the faces checked must carry nearly all of the area.
void expect_contains_padded(const OcclusionProxy& proxy, std::span<const glm::vec3> object, float pad,
                            float clearance) {
  constexpr double min_altitude_mm = 0.1, tolerance_mm = 0.02;
  glm::dvec3 center(0.0);
  for (const glm::vec3& p : object) center += glm::dvec3(p) / double(object.size());
  double area = 0.0, checked_area = 0.0, worst_clearance = 1e30;
  std::size_t inward = 0, nonconvex = 0, too_close = 0;
  for (std::size_t t = 0; t < proxy.indices.size(); t += 3) {
    const glm::dvec3 a(proxy.vertex(proxy.indices[t], pad)), b(proxy.vertex(proxy.indices[t + 1], pad)),
        c(proxy.vertex(proxy.indices[t + 2], pad));
    const glm::dvec3 cross = glm::cross(b - a, c - a);
    const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    area += 0.5 * glm::length(cross);
    if (glm::length(cross) < min_altitude_mm * longest) continue;
    checked_area += 0.5 * glm::length(cross);
    const glm::dvec3 n = glm::normalize(cross);
    const double plane = glm::dot(n, a);
    inward += glm::dot(n, center) > plane;
    for (std::size_t i = 0; i < proxy.corners.size(); ++i) {
      nonconvex += glm::dot(n, glm::dvec3(proxy.vertex(i, pad))) > plane + tolerance_mm;
    }
    double farthest = -1e30;
    for (const glm::vec3& p : object) farthest = std::max(farthest, glm::dot(n, glm::dvec3(p)));
    worst_clearance = std::min(worst_clearance, plane - farthest);
    too_close += plane - farthest < clearance - tolerance_mm;
  }
  EXPECT_GT(checked_area, 0.99 * area);
  EXPECT_EQ(inward, 0u);
  EXPECT_EQ(nonconvex, 0u);
  EXPECT_EQ(too_close, 0u) << "pad " << pad << ": a face stands only " << worst_clearance
                           << " mm off the object, not " << clearance;
}

constexpr float margin = 0.5f;

TEST(OcclusionProxy, TheBrainsProxyContainsEveryPointWithinTheMarginAndThePad) {
  // A smaller brain than Table I's, as the check is faces x vertices; the same folds and fissure.
  const glm::mat4 transform = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(10.0f, -20.0f, 30.0f)),
                                          0.4f, glm::vec3(0.3f, 1.0f, 0.2f));
  const std::vector<glm::vec3> brain = transformed(make_brain_phantom(12000), transform);
  const std::optional<OcclusionProxy> proxy = make_occlusion_proxy(brain, margin);
  ASSERT_TRUE(proxy);
  std::printf("brain of %zu vertices: proxy of %zu vertices, %zu triangles\n", brain.size(),
              proxy->corners.size(), proxy->indices.size() / 3);
  EXPECT_LT(proxy->indices.size() / 3, 3000u) << "the proxy's size should not grow with the mesh's";
  expect_closed(*proxy);
  for (float pad : {0.0f, 4.0f, 25.0f}) expect_contains_padded(*proxy, brain, pad, margin + pad);
}

TEST(OcclusionProxy, OnASphereItStandsWithinAFewPercentOfTheRadius) {
  const std::vector<glm::vec3> sphere = transformed(make_sphere(30.0f, 4000), glm::mat4(1.0f));
  const std::optional<OcclusionProxy> proxy = make_occlusion_proxy(sphere, margin);
  ASSERT_TRUE(proxy);
  const float pad = 2.0f;
  float farthest = 0.0f;
  for (std::size_t i = 0; i < proxy->corners.size(); ++i) {
    farthest = std::max(farthest, glm::length(proxy->vertex(i, pad)));
  }
  std::printf("sphere of radius 30 mm, margin %.1f, pad %.1f: proxy reaches %.3f mm\n", margin, pad,
              farthest);
  EXPECT_LE(farthest, 1.02f * (30.0f + margin) + std::sqrt(3.0f) * pad);
  expect_contains_padded(*proxy, sphere, pad, margin + pad);
}

TEST(OcclusionProxy, AFlatMeshGetsASlabAsThickAsTheMargin) {
  const std::vector<glm::vec3> flat = transformed(make_grid(50.0f, 20), glm::mat4(1.0f));  // z = 0
  const std::optional<OcclusionProxy> slab = make_occlusion_proxy(flat, margin);
  ASSERT_TRUE(slab);
  expect_closed(*slab);
  float thickness = 0.0f;
  for (const glm::vec3& corner : slab->corners) thickness = std::max(thickness, std::abs(corner.z));
  EXPECT_NEAR(thickness, margin, 1e-4f);
  for (float pad : {0.0f, 3.0f}) expect_contains_padded(*slab, flat, pad, margin + pad);

  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(1.0f, 0.2f, 0.0f));
  const std::vector<glm::vec3> plane = transformed(make_grid(50.0f, 20), tilt);
  const std::optional<OcclusionProxy> tilted = make_occlusion_proxy(plane, margin);
  ASSERT_TRUE(tilted);
  expect_closed(*tilted);
  for (float pad : {0.0f, 3.0f}) expect_contains_padded(*tilted, plane, pad, margin + pad);

  // Fewer points than a hull needs: still a proxy around them.
  const glm::vec3 triangle[] = {{0, 0, 0}, {100, 0, 0}, {0, 100, 50}};
  const std::optional<OcclusionProxy> three = make_occlusion_proxy(triangle, margin);
  ASSERT_TRUE(three);
  expect_contains_padded(*three, triangle, 1.0f, margin + 1.0f);
  EXPECT_FALSE(make_occlusion_proxy({}, margin)) << "no points, no proxy";
}

}  // namespace
}  // namespace palpate::gl
