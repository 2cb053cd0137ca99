// The CPU reference of the deformation against closed-form values.
#include "palpate/core/deform.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <vector>

namespace palpate {
namespace {

TEST(DentGaussian, MatchesClosedForm) {
  EXPECT_FLOAT_EQ(dent_gaussian(0.0f, 3.0f, 5.0f), 3.0f);
  EXPECT_NEAR(dent_gaussian(5.0f, 3.0f, 5.0f), 3.0f * std::exp(-0.5f), 1e-6f);
  EXPECT_NEAR(dent_gaussian(10.0f, 2.0f, 5.0f), 2.0f * std::exp(-2.0f), 1e-6f);
}

TEST(DentSlope, IsTheDerivativeOfTheGaussian) {
  for (float d : {0.0f, 0.5f, 2.0f, 5.0f, 9.0f, 14.0f}) {
    const float h = 1e-2f;
    const float numeric = (dent_gaussian(d + h, 3.0f, 5.0f) - dent_gaussian(d - h, 3.0f, 5.0f)) / (2 * h);
    EXPECT_NEAR(dent_slope(d, 3.0f, 5.0f), numeric, 1e-4f) << "d = " << d;
  }
  EXPECT_LT(dent_slope(1.0f, 3.0f, 5.0f), 0.0f);  // the paper's printed exponent sign would grow instead
}

TEST(DisplacedPosition, ReachesTheHipAtTheContactPoint) {
  const Dent dent{{1.0f, 2.0f, 0.0f}, 2.5f, 4.0f};
  const glm::vec3 moved = displaced_position(dent.center_mm, {0, 0, 1}, {&dent, 1});
  EXPECT_NEAR(glm::distance(moved, glm::vec3(1.0f, 2.0f, -2.5f)), 0.0f, 1e-6f);
}

TEST(DisplacedPosition, SkipsBeyondTheCutoffAndSuperposes) {
  const std::vector<Dent> dents{{{0, 0, 0}, 1.0f, 2.0f}, {{3, 0, 0}, 2.0f, 2.0f}};
  const glm::vec3 far = displaced_position({8.01f, 0, 0}, {0, 0, 1}, {dents.data(), 1});
  EXPECT_EQ(far, glm::vec3(8.01f, 0, 0));
  const glm::vec3 between = displaced_position({1.5f, 0, 0}, {0, 0, 1}, dents);
  EXPECT_NEAR(between.z, -(dent_gaussian(1.5f, 1.0f, 2.0f) + dent_gaussian(1.5f, 2.0f, 2.0f)), 1e-6f);
}

// A host that works in eye space and metres gets the same dent: map the world-millimetre answer into
// its space, or map the dent and compute there.
TEST(DentInSpace, GivesTheSameDeformationInTheHostsSpace) {
  const glm::mat4 view = glm::lookAt(glm::vec3(40, -120, 60), glm::vec3(0, 0, 10), glm::vec3(0, 0, 1));
  const glm::mat4 to_eye_metres = glm::scale(glm::mat4(1.0f), glm::vec3(1e-3f)) * view;
  const Dent world{{3.0f, -1.0f, 20.0f}, 4.0f, 6.0f};
  const Dent eye = dent_in_space(world, to_eye_metres);
  EXPECT_NEAR(eye.depth_mm, 4e-3f, 1e-9f);
  EXPECT_NEAR(eye.sigma_mm, 6e-3f, 1e-9f);
  const glm::mat3 rotation(view);
  for (const glm::vec3 v :
       {glm::vec3(5.0f, 2.0f, 20.0f), glm::vec3(3.0f, -1.0f, 20.0f), glm::vec3(-9.0f, 0.0f, 19.0f)}) {
    const glm::vec3 n = glm::normalize(glm::vec3(0.1f, -0.2f, 1.0f));
    const glm::vec3 in_world =
        glm::vec3(to_eye_metres * glm::vec4(displaced_position(v, n, {&world, 1}), 1.0f));
    const glm::vec3 in_eye =
        displaced_position(glm::vec3(to_eye_metres * glm::vec4(v, 1.0f)), rotation * n, {&eye, 1});
    EXPECT_NEAR(glm::distance(in_world, in_eye), 0.0f, 1e-7f);
    const glm::vec3 tilted_world = rotation * perturbed_normal(n, v, {&world, 1});
    const glm::vec3 tilted_eye =
        perturbed_normal(rotation * n, glm::vec3(to_eye_metres * glm::vec4(v, 1.0f)), {&eye, 1});
    EXPECT_NEAR(glm::distance(tilted_world, tilted_eye), 0.0f, 1e-5f);
  }
}

TEST(PerturbedNormal, TiltsTowardTheContactByTheSlopeAngle) {
  const Dent dent{{0, 0, 0}, 3.0f, 5.0f};
  const float d = 4.0f;
  const glm::vec3 n = perturbed_normal({0, 0, 1}, {d, 0, 0}, {&dent, 1});
  // The surface z = -G(x) has normal (G'(x), 0, 1) normalised: it leans toward the contact (-x).
  const glm::vec3 expected = glm::normalize(glm::vec3(dent_slope(d, 3.0f, 5.0f), 0.0f, 1.0f));
  EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(n, expected), 1.0f, 1e-6f);
  EXPECT_LT(n.x, 0.0f);
}

TEST(PerturbedNormal, IsUnchangedAtTheContactPointAndFarAway) {
  const Dent dent{{0, 0, 0}, 3.0f, 5.0f};
  EXPECT_EQ(perturbed_normal({0, 0, 1}, {0, 0, 0}, {&dent, 1}), glm::vec3(0, 0, 1));
  EXPECT_EQ(perturbed_normal({0, 0, 1}, {0, 0, 5}, {&dent, 1}), glm::vec3(0, 0, 1));  // N parallel to VC
  EXPECT_EQ(perturbed_normal({0, 0, 1}, {25, 0, 0}, {&dent, 1}), glm::vec3(0, 0, 1));
}

TEST(DeformMesh, MatchesTheAnalyticSurfaceOfAFinePlane) {
  // A 41 x 41 grid, 0.5 mm apart, dented at its centre: vertex normals of the deformed triangles must
  // agree with the analytic normal (G' r_hat, 1) of the surface z = -G(r).
  Mesh plane;
  const int n = 41;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      plane.positions_mm.push_back({(i - n / 2) * 0.5f, (j - n / 2) * 0.5f, 0.0f});
      plane.normals.push_back({0, 0, 1});
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      plane.indices.insert(plane.indices.end(), {a, b, d, a, d, c});
    }
  }
  const Dent dent{{0, 0, 0}, 1.5f, 3.0f};
  Mesh out;
  deform_mesh(plane, glm::mat4(1.0f), {&dent, 1}, out);
  ASSERT_EQ(out.vertex_count(), plane.vertex_count());
  float worst = 0.0f;
  for (std::size_t v = 0; v < plane.vertex_count(); ++v) {
    const glm::vec3 p = plane.positions_mm[v];
    const float r = glm::length(glm::vec2(p));
    if (std::abs(p.x) > 9.0f || std::abs(p.y) > 9.0f) continue;  // boundary vertices lack neighbours
    const float expected_z = r < dent_cutoff_sigmas * 3.0f ? -dent_gaussian(r, 1.5f, 3.0f) : 0.0f;
    EXPECT_NEAR(out.positions_mm[v].z, expected_z, 1e-6f);
    const glm::vec3 analytic =
        r > 0 ? glm::normalize(glm::vec3(dent_slope(r, 1.5f, 3.0f) * glm::vec2(p) / r, 1.0f))
              : glm::vec3(0, 0, 1);
    worst = std::max(worst, std::acos(std::min(1.0f, glm::dot(out.normals[v], analytic))));
    EXPECT_NEAR(glm::dot(perturbed_normal({0, 0, 1}, p, {&dent, 1}), analytic), 1.0f, 1e-5f);
  }
  EXPECT_LT(glm::degrees(worst), 1.5f);
}

}  // namespace
}  // namespace palpate

namespace palpate {
namespace {

// The widened dent's steepest slope, found by sampling G', is the limit; a shallow dent keeps its sigma;
// the contact point still reaches the tip (G(0) = p).
TEST(DentSlopeLimit, WidensOnlyWhatIsTooSteep) {
  const Dent shallow{{0, 0, 0}, 2.0f, 4.0f}, deep{{0, 0, 0}, 8.0f, 4.0f};
  EXPECT_EQ(dent_with_slope_limit(shallow, 0.75f).sigma_mm, 4.0f);  // slope 0.30
  const Dent widened = dent_with_slope_limit(deep, 0.75f);
  EXPECT_GT(widened.sigma_mm, 4.0f);
  float steepest = 0.0f;
  for (float d = 0.0f; d < 4.0f * widened.sigma_mm; d += 0.001f)
    steepest = std::max(steepest, -dent_slope(d, widened.depth_mm, widened.sigma_mm));
  EXPECT_NEAR(steepest, 0.75f, 1e-4f);
  EXPECT_EQ(dent_gaussian(0.0f, widened.depth_mm, widened.sigma_mm), 8.0f);
}

}  // namespace
}  // namespace palpate
