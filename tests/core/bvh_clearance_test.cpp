// Bvh::clear_above: a segment it calls clear meets no triangle, where another sheet of surface passes
// close above a face (a thin wall, a fold, a face standing on another) and on the bumpy sphere's bumps
// and the brain phantom's folds; and it calls clear the walks of a slide over a smooth surface, which
// is what spares the proxy their casts.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <random>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/testing/reference_geometry.hpp"

namespace palpate {
namespace {

constexpr double epsilon = 1e-3;  // the proxy's default surface epsilon, mm

Scene scene_of(std::vector<Mesh> meshes) {
  Scene scene;
  for (Mesh& mesh : meshes) scene.objects.push_back({"object", std::move(mesh), glm::mat4(1.0f), {}, {}});
  return scene;
}

Mesh triangle_mesh(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  Mesh mesh;
  mesh.positions_mm = {a, b, c};
  mesh.indices = {0, 1, 2};
  return mesh;
}

// Reference: whether the segment meets any triangle of the tree, either face (Moller-Trumbore over
// every triangle, an algorithm apart from the tree's cast).
bool brute_meets(const Bvh& bvh, const glm::dvec3& from, const glm::dvec3& to) {
  for (std::uint32_t i = 0; i < bvh.triangle_count(); ++i) {
    const auto& v = bvh.triangle(i).vertices;
    if (testing::segment_meets_triangle(from, to, glm::dvec3(v[0]), glm::dvec3(v[1]), glm::dvec3(v[2])))
      return true;
  }
  return false;
}

// A point over triangle `primitive`: barycentric (u, v) from its first corner (outside it when they
// leave [0, 1]), `height` above its plane.
glm::dvec3 over(const Bvh& bvh, std::uint32_t primitive, double u, double v, double height) {
  const auto& t = bvh.triangle(primitive).vertices;
  const glm::dvec3 a(t[0]), b(t[1]), c(t[2]);
  const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
  return a + u * (b - a) + v * (c - a) + height * normal;
}

struct Tally {
  long asked = 0, meeting = 0;  // segments, and those that meet a triangle
  long clear = 0, met = 0;      // those called clear, and those of them that meet one
};

// Segments from just above a random triangle, as a proxy walks, steps over an edge or climbs: asks
// clear_above for each and checks that a clear one meets nothing (by `meets`).
// Their ends lie over the triangle or up to `out` of its size beyond its sides.
template <class Meets>
Tally check_segments(const Bvh& bvh, std::mt19937& rng, long count, double max_height, double out,
                     Meets meets) {
  std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(bvh.triangle_count() - 1));
  std::uniform_real_distribution<double> spread(-out, 1.0 + out), height(0.0, max_height);
  Tally tally;
  while (tally.asked < count) {
    const std::uint32_t t = pick(rng);
    double u = spread(rng), v = spread(rng);
    if (u + v > 1.0 + out) u = 1.0 + out - u, v = 1.0 + out - v;
    double u2 = spread(rng), v2 = spread(rng);
    if (u2 + v2 > 1.0 + out) u2 = 1.0 + out - u2, v2 = 1.0 + out - v2;
    const glm::dvec3 from = over(bvh, t, u, v, height(rng)), to = over(bvh, t, u2, v2, height(rng));
    ++tally.asked;
    const bool hit = meets(from, to);
    tally.meeting += hit;
    if (!bvh.clear_above(t, from, to)) continue;
    ++tally.clear;
    tally.met += hit;
    EXPECT_FALSE(hit) << "triangle " << t << " from " << from.x << ' ' << from.y << ' ' << from.z << " to "
                      << to.x << ' ' << to.y << ' ' << to.z;
    if (hit) break;
  }
  return tally;
}

TEST(BvhClearance, NoSegmentItCallsClearMeetsASheetFoldOrWallCloseAboveAFace) {
  // A flat grid of 1 mm cells and, over its middle, what a walk a micrometre above it could run into:
  // a sheet 3 micrometres above, folds rising from a grid line at 30 and 60 degrees, a face standing
  // on the grid and one leaning low over it.
  const float s60 = std::sqrt(3.0f);
  const Scene scene = scene_of({
      make_grid(10.0f, 10),
      triangle_mesh({-1.0f, -1.0f, 0.003f}, {0.5f, -1.0f, 0.003f}, {-1.0f, 0.5f, 0.003f}),
      triangle_mesh({2.0f, -3.0f, 0.0f}, {2.0f, -1.0f, 0.0f}, {2.5f, -2.0f, 0.5f * s60}),
      triangle_mesh({-2.0f, 2.0f, 0.0f}, {-2.0f, 3.0f, 0.0f}, {-2.0f - s60, 2.5f, 1.0f}),
      triangle_mesh({1.2f, 1.2f, -0.5f}, {1.8f, 1.5f, -0.5f}, {1.5f, 1.4f, 0.5f}),
      triangle_mesh({-3.5f, -3.5f, 0.0f}, {-2.5f, -3.5f, 0.0f}, {-3.0f, -3.0f, 0.0002f}),
  });
  const Bvh bvh = Bvh::build(scene);
  std::mt19937 rng(3);
  const Tally tally = check_segments(
      bvh, rng, 400'000, 6.0 * epsilon, 0.2,
      [&](const glm::dvec3& from, const glm::dvec3& to) { return brute_meets(bvh, from, to); });
  // Many segments are clear (22% measured; the others leave their face's space or pass a feature), many
  // meet a feature (2.2%), and none of those is clear.
  EXPECT_GT(tally.clear, tally.asked / 5);
  EXPECT_GT(tally.meeting, tally.asked / 50);
  EXPECT_EQ(tally.met, 0);

  // Where a walk starts beside a feature: whether it is clear, at what height.
  const auto clear_walk = [&](glm::dvec3 from, glm::dvec3 to, double height) {
    const BvhHit below = bvh.closest_point(from, 1e-3, std::vector<std::uint8_t>{1, 0, 0, 0, 0, 0});
    EXPECT_TRUE(below.hit());
    const glm::dvec3 up(0.0, 0.0, height);
    return bvh.clear_above(below.primitive, from + up, to + up);
  };
  // Under the sheet 3 micrometres up: clear a micrometre above the grid, not 4 micrometres above it.
  EXPECT_TRUE(clear_walk({-0.6, -0.6, 0.0}, {-0.5, -0.6, 0.0}, epsilon));
  EXPECT_FALSE(clear_walk({-0.6, -0.6, 0.0}, {-0.5, -0.6, 0.0}, 4.0 * epsilon));
  // Toward the grid line the folds rise from: the fold at 60 degrees enters the space above the faces
  // beside it, the one at 30 degrees stays out of it.
  EXPECT_FALSE(clear_walk({1.99, -2.3, 0.0}, {1.999, -2.3, 0.0}, epsilon));
  EXPECT_TRUE(clear_walk({-1.99, 2.5, 0.0}, {-1.999, 2.5, 0.0}, epsilon));
  // Next to where the standing face pierces the grid, and over the face leaning low over it.
  EXPECT_FALSE(clear_walk({1.5, 1.4, 0.0}, {1.52, 1.41, 0.0}, epsilon));
  EXPECT_FALSE(clear_walk({-3.0, -3.4, 0.0}, {-3.1, -3.45, 0.0}, epsilon));
}

TEST(BvhClearance, OverASharpCornerTheSpaceReachesFarBeyondIt) {
  // A corner of 10 degrees: a tenth of a millimetre up, the space above the triangle reaches over a
  // millimetre beyond it, and a small sheet there is in it.
  const glm::dvec3 bisector = glm::normalize(glm::dvec3(-1.0, -std::tan(glm::radians(5.0)), 0.0));
  const glm::dvec3 centre = 1.5 * bisector + glm::dvec3(0.0, 0.0, 0.15);
  const auto at = [&](double dx, double dy) { return glm::vec3(centre + glm::dvec3(dx, dy, 0.0)); };
  const Scene scene = scene_of({
      triangle_mesh({0.0f, 0.0f, 0.0f}, {10.0f, 0.0f, 0.0f},
                    {10.0f, float(10.0 * std::tan(glm::radians(10.0))), 0.0f}),
      triangle_mesh(at(-0.05, -0.05), at(0.05, -0.05), at(0.0, 0.05)),
  });
  const Bvh bvh = Bvh::build(scene);
  const BvhHit below = bvh.closest_point({5.0, 0.1, 0.0}, 1e-3);
  ASSERT_TRUE(below.hit());
  const glm::dvec3 through = centre + glm::dvec3(0.0, 0.0, 0.01);
  ASSERT_TRUE(brute_meets(bvh, through, centre - glm::dvec3(0.0, 0.0, 0.01)));
  EXPECT_FALSE(bvh.clear_above(below.primitive, through, centre - glm::dvec3(0.0, 0.0, 0.01)));
  // Just under the sheet, where the space is as wide, it is clear.
  EXPECT_TRUE(bvh.clear_above(below.primitive, centre - glm::dvec3(0.0, 0.0, 0.01),
                              centre - glm::dvec3(0.0, 0.0, 0.015)));
}

TEST(BvhClearance, NoSegmentItCallsClearMeetsTheBumpySphereOrTheBrainPhantom) {
  for (Mesh mesh : {make_bumpy_sphere(50.0f, 1.5f, 60000), make_brain_phantom()}) {
    const Scene scene = scene_of({std::move(mesh)});
    const Bvh bvh = Bvh::build(scene);
    std::mt19937 rng(11);
    // The tree's own cast as the reference here (checked against a brute force elsewhere), with the
    // start tolerance the proxy gives it.
    const auto meets = [&](const glm::dvec3& from, const glm::dvec3& to) {
      return bvh.first_hit(from, to, Faces::both, 1e-3 * epsilon).hit();
    };
    // As low as a proxy walks.
    const Tally low = check_segments(bvh, rng, 300'000, 20.0 * epsilon, 0.2, meets);
    // 28% and 23% clear, 9% and 14% meeting the surface, measured.
    EXPECT_GT(low.clear, low.asked / 5);
    EXPECT_GT(low.meeting, low.asked / 20);
    EXPECT_EQ(low.met, 0);
    // Through the whole space up to and over its ceiling (a tenth of the longest edge), reaching
    // far beyond the sides.
    const Tally high = check_segments(bvh, rng, 300'000, 0.12 * bvh.typical_triangle_size_mm(), 0.5, meets);
    // 7% and 5% clear, 5% and 13% meeting the surface, measured.
    EXPECT_GT(high.clear, high.asked / 25);
    EXPECT_GT(high.meeting, high.asked / 25);
    EXPECT_EQ(high.met, 0);
  }
}

TEST(BvhClearance, ASlideOverASmoothSurfaceWalksInTheClear) {
  const Scene scene = scene_of({make_sphere(50.0f, 30000)});
  const Bvh bvh = Bvh::build(scene);
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(bvh.triangle_count() - 1));
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  long walks = 0, clear = 0;
  for (; walks < 20'000; ++walks) {
    // From a point of the face or of its edge, handed over from the face across (an epsilon above that
    // face), to another point of the face, an epsilon above it.
    const std::uint32_t t = pick(rng);
    const double u = fraction(rng), v = fraction(rng) * (1.0 - u);
    const std::uint32_t across = bvh.neighbour(t, 0);
    ASSERT_NE(across, Bvh::no_neighbour);
    const glm::dvec3 on_edge = over(bvh, t, u, 0.0, 0.0);
    const auto& n = bvh.triangle(across).vertices;
    const glm::dvec3 across_normal =
        glm::normalize(glm::cross(glm::dvec3(n[1]) - glm::dvec3(n[0]), glm::dvec3(n[2]) - glm::dvec3(n[0])));
    const glm::dvec3 from = walks % 2 ? on_edge + epsilon * across_normal : over(bvh, t, v, u, epsilon);
    clear += bvh.clear_above(t, from, over(bvh, t, u * v, v, epsilon));
  }
  EXPECT_GT(clear, walks * 99 / 100);
}

}  // namespace
}  // namespace palpate
