// The proxy on simple shapes, against the analytic god-object answer.
#include "palpate/haptics/proxy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "palpate/core/shapes.hpp"
#include "palpate/haptics/force.hpp"
#include "palpate/testing/haptic_scenarios.hpp"
#include "palpate/testing/test_shapes.hpp"

namespace palpate {
namespace {

using testing::scene_of;

constexpr double eps = ProxyParams{}.surface_epsilon_mm;

// Moves the HIP in `steps` equal ticks from where it is to `to`; returns the last contact.
Contact move(ProxyState& state, const Bvh& bvh, glm::dvec3& hip, glm::dvec3 to, int steps) {
  const glm::dvec3 from = hip;
  Contact c;
  for (int i = 1; i <= steps; ++i) {
    hip = from + (to - from) * (double(i) / steps);
    c = proxy_step(state, bvh, glm::vec3(hip));
  }
  return c;
}

void expect_near(glm::dvec3 got, glm::dvec3 want, double tolerance, const char* what) {
  EXPECT_LE(glm::length(got - want), tolerance)
      << what << ": got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", "
      << want.y << ", " << want.z << ")";
}

// The 40 mm cube: faces at +/-20.
class ProxyOnCube : public ::testing::Test {
 protected:
  Scene scene = scene_of("cube", make_box(glm::vec3(40.0f)));
  Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{3.0, -4.0, 30.0};

  void SetUp() override { state.reset(glm::vec3(hip)); }
};

TEST_F(ProxyOnCube, FollowsTheHipInFreeSpace) {
  const Contact c = move(state, bvh, hip, {-10.0, 25.0, 31.0}, 20);
  EXPECT_FALSE(c.in_contact());
  expect_near(state.position_mm, hip, 1e-12, "proxy");
  EXPECT_EQ(glm::dvec3(c.point_mm), glm::dvec3(c.hip_mm));
}

// Free, it keeps the leaves around itself (a box 0.7 typical triangles wide either side) so that the
// tick that meets the surface casts among them; far from everything the box is empty. (A step that
// starts outside the box gathers it around where it starts.)
TEST_F(ProxyOnCube, KeepsTheLeavesAroundItInFreeSpace) {
  move(state, bvh, hip, {3.0, -4.0, 200.0}, 2);
  EXPECT_EQ(state.neighbourhood.count, 0);
  move(state, bvh, hip, {3.0, -4.0, 20.5}, 10);
  EXPECT_FALSE(state.in_contact());
  EXPECT_GT(state.neighbourhood.count, 0);
  EXPECT_TRUE(state.neighbourhood.covers(state.position_mm));
  EXPECT_TRUE(bvh.gathered_here(state.neighbourhood));
  const Contact c = move(state, bvh, hip, {3.0, -4.0, 19.5}, 1);
  ASSERT_TRUE(c.in_contact());
  expect_near(state.position_mm, {3.0, -4.0, 20.0 + eps}, 1e-9, "proxy");
}

// Between ticks (proxy_prepare) the proxy gathers its neighbourhood around where it is, so that its
// steps almost never gather it themselves; and every step ends where it ends without (the neighbourhood
// only speeds the searches up). Sphere-slide cycles on the Table I skin-sized bumpy sphere.
TEST(ProxyPrepare, GathersBetweenStepsAndChangesNoAnswer) {
  const Scene scene = scene_of("bumpy sphere", make_bumpy_sphere(50.0f, 1.5f, 53021));
  const Bvh bvh = Bvh::build(scene);
  const testing::BumpySphereOracle oracle(50.0f, 1.5f);
  int steps = 0, contact_steps = 0, gathered_in_step = 0, gathered_between = 0;
  const auto box_of = [](const ProxyState& s) {
    return std::pair(s.neighbourhood.low, s.neighbourhood.high);
  };
  for (const SampledPath& cycle : testing::sphere_slide(oracle, {.cycles = 3, .seed = 5})) {
    ProxyState plain, prepared;
    for (const PathSample& sample : cycle.samples()) {
      proxy_step(plain, bvh, sample.position_mm);
      const auto before_step = box_of(prepared);
      proxy_step(prepared, bvh, sample.position_mm);
      ASSERT_EQ(prepared.position_mm, plain.position_mm) << "step " << steps;
      ASSERT_EQ(prepared.constraint_count, plain.constraint_count) << "step " << steps;
      gathered_in_step += box_of(prepared) != before_step;
      const auto before_prepare = box_of(prepared);
      proxy_prepare(prepared, bvh);
      gathered_between += box_of(prepared) != before_prepare;
      if (prepared.in_contact()) {
        EXPECT_TRUE(prepared.neighbourhood.covers(prepared.position_mm)) << "step " << steps;
        ++contact_steps;
      }
      ++steps;
    }
  }
  EXPECT_GT(contact_steps, 3000);
  // Measured: 943 gathers between the 12,000 steps (6,838 in contact), 3 within them.
  EXPECT_GT(gathered_between, 700);
  EXPECT_LE(gathered_in_step, 10);
}

TEST_F(ProxyOnCube, RestsOnTheFaceAboveTheHipWithTheFaceNormal) {
  const Contact c = move(state, bvh, hip, {3.0, -4.0, 17.5}, 50);
  ASSERT_TRUE(c.in_contact());
  expect_near(state.position_mm, {3.0, -4.0, 20.0 + eps}, 1e-9, "proxy");
  EXPECT_EQ(c.object, 0);
  const Mesh& cube = scene.objects[0].mesh;
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(cube.positions_mm[cube.indices[3 * std::size_t(c.triangle) + k]].z, 20.0f);
  EXPECT_NEAR(c.normal.z, 1.0f, 1e-6f);
  EXPECT_NEAR(c.depth_mm, 2.5 + eps, 1e-5);
  EXPECT_NEAR(glm::length(glm::vec3(c.point_mm) - c.hip_mm), c.depth_mm, 1e-5f);
  EXPECT_EQ(state.constraint_count, 1);
}

TEST_F(ProxyOnCube, SlidesOnTheFaceAcrossItsTrianglesExactlyAboveTheHip) {
  move(state, bvh, hip, {3.0, -4.0, 17.5}, 50);
  const glm::dvec3 from = hip;
  for (int i = 1; i <= 500; ++i) {
    hip = from + (glm::dvec3(-15.0, 12.0, 18.5) - from) * (i / 500.0);
    const Contact c = proxy_step(state, bvh, glm::vec3(hip));
    ASSERT_TRUE(c.in_contact()) << "step " << i;
    const glm::dvec3 h(c.hip_mm);  // the HIP as the proxy saw it, in float
    expect_near(state.position_mm, {h.x, h.y, 20.0 + eps}, 1e-9, "proxy");
  }
}

TEST_F(ProxyOnCube, ReleasesAsSoonAsTheTipLeaves) {
  move(state, bvh, hip, {3.0, -4.0, 17.5}, 50);
  Contact c = move(state, bvh, hip, {3.0, -4.0, 20.0 - 1e-2}, 10);
  EXPECT_TRUE(c.in_contact());
  c = move(state, bvh, hip, {3.0, -4.0, 20.0 + 1e-2}, 1);
  EXPECT_FALSE(c.in_contact());
  expect_near(state.position_mm, glm::dvec3(c.hip_mm), 1e-12, "proxy");
  EXPECT_EQ(state.constraint_count, 0);
}

TEST_F(ProxyOnCube, HoldsToTheTopFaceWhenPushedDeepTowardTheSide) {
  // The god-object keeps to the face it entered, even where another face is nearer the tip.
  move(state, bvh, hip, {15.0, 0.0, 17.0}, 50);
  const Contact c = move(state, bvh, hip, {19.5, 0.0, 5.0}, 200);
  ASSERT_TRUE(c.in_contact());
  expect_near(state.position_mm, {19.5, 0.0, 20.0 + eps}, 1e-9, "proxy");
}

TEST_F(ProxyOnCube, SlidesOffAConvexEdgeOnceTheTipIsPastIt) {
  move(state, bvh, hip, {15.0, 0.0, 17.0}, 50);
  const glm::dvec3 from = hip;
  for (int i = 1; i <= 400; ++i) {
    hip = from + (glm::dvec3(25.0, 0.0, 15.0) - from) * (i / 400.0);
    proxy_step(state, bvh, glm::vec3(hip));
    const glm::dvec3 p = state.position_mm;
    ASSERT_FALSE(p.x < 20.0 && p.z < 20.0) << "proxy inside the cube at step " << i;
  }
  const Contact c = proxy_step(state, bvh, glm::vec3(hip));
  EXPECT_FALSE(c.in_contact());
  expect_near(state.position_mm, glm::dvec3(c.hip_mm), 1e-12, "proxy");
}

TEST_F(ProxyOnCube, AnEdgeMetHeadOnHoldsTheProxyOnOneOfItsFaces) {
  hip = {30.0, 1.0, 30.0};
  state.reset(glm::vec3(hip));
  const Contact c = move(state, bvh, hip, {19.0, 1.0, 19.0}, 40);  // straight through the edge
  ASSERT_TRUE(c.in_contact());
  const glm::dvec3 on_top{19.0, 1.0, 20.0 + eps}, on_side{20.0 + eps, 1.0, 19.0};
  const double error =
      std::min(glm::length(state.position_mm - on_top), glm::length(state.position_mm - on_side));
  EXPECT_LE(error, 1e-9);
  EXPECT_NEAR(c.depth_mm, 1.0 + eps, 1e-5);
}

TEST_F(ProxyOnCube, AVertexMetHeadOnHoldsTheProxyOnOneOfItsFaces) {
  hip = {30.0, 30.0, 30.0};
  state.reset(glm::vec3(hip));
  const Contact c = move(state, bvh, hip, {19.0, 19.0, 19.0}, 40);  // straight through the corner
  ASSERT_TRUE(c.in_contact());
  double error = 1e9;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 want(19.0);
    want[axis] = 20.0 + eps;
    error = std::min(error, glm::length(state.position_mm - want));
  }
  EXPECT_LE(error, 1e-9);
}

// Force on a flat face: exactly k p along the face normal.
TEST_F(ProxyOnCube, ForceOnAFaceIsStiffnessTimesDepthAlongTheNormal) {
  const Material material{.stiffness_n_per_mm = 0.8f, .damping_ns_per_m = 3.0f};
  for (double depth : {0.01, 0.5, 2.0, 3.7}) {
    const Contact c = move(state, bvh, hip, {3.0, -4.0, 20.0 - depth}, 20);
    ASSERT_TRUE(c.in_contact());
    const ForceResult f = spring_damper(c, glm::vec3(0.0f), material, 100.0f);
    const double p = 20.0 + eps - double(c.hip_mm.z);
    // Exact up to the float rounding of the contact's coordinates near 20 mm (2e-6 mm).
    EXPECT_EQ(f.force_n.x, 0.0f);
    EXPECT_EQ(f.force_n.y, 0.0f);
    EXPECT_NEAR(f.force_n.z, 0.8 * p, 0.8 * 4e-6);
    EXPECT_FALSE(f.clamped);
  }
}

// A cube-shaped cavity (walls at +/-10) in a 60 mm block: concave creases and corners.
class ProxyInCavity : public ::testing::Test {
 protected:
  Scene scene = scene_of("hollow box", testing::make_hollow_box(60.0f, 20.0f));
  Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{0.0, 0.0, 0.0};

  void SetUp() override { state.reset(glm::vec3(hip)); }
};

TEST_F(ProxyInCavity, ACornerHoldsTheProxyAtTheCorner) {
  const Contact c = move(state, bvh, hip, {14.0, 13.0, 12.0}, 100);
  ASSERT_TRUE(c.in_contact());
  const glm::dvec3 corner(10.0 - eps);
  expect_near(state.position_mm, corner, 1e-9, "proxy");
  EXPECT_EQ(state.constraint_count, 3);
  expect_near(glm::dvec3(c.normal), glm::normalize(corner - glm::dvec3(c.hip_mm)), 1e-6, "normal");
  EXPECT_NEAR(c.depth_mm, glm::length(corner - glm::dvec3(c.hip_mm)), 1e-5);
}

TEST_F(ProxyInCavity, ACreaseHoldsTheProxyOnTheCreaseLine) {
  const Contact c = move(state, bvh, hip, {14.0, 13.0, 2.0}, 100);
  ASSERT_TRUE(c.in_contact());
  expect_near(state.position_mm, {10.0 - eps, 10.0 - eps, 2.0}, 1e-9, "proxy");
  EXPECT_EQ(state.constraint_count, 2);
  // Along the crease the proxy slides freely.
  move(state, bvh, hip, {14.0, 13.0, -7.0}, 100);
  expect_near(state.position_mm, {10.0 - eps, 10.0 - eps, -7.0}, 1e-9, "proxy");
  // Back into the room: released.
  const Contact back = move(state, bvh, hip, {0.0, 0.0, 0.0}, 100);
  EXPECT_FALSE(back.in_contact());
  expect_near(state.position_mm, glm::dvec3(0.0), 1e-12, "proxy");
}

// A pit: a square cup whose four faces meet at an apex 5 mm below the rim, on a block. From above,
// the apex is a concave vertex of four faces.
Mesh make_pit() {
  Mesh m;
  m.positions_mm = {{-10, -10, 0},   {10, -10, 0},   {10, 10, 0},   {-10, 10, 0},  {0, 0, -5},
                    {-10, -10, -20}, {10, -10, -20}, {10, 10, -20}, {-10, 10, -20}};
  m.indices = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4,                                       // the cup
               5, 7, 6, 5, 8, 7,                                                         // bottom
               0, 5, 6, 0, 6, 1, 1, 6, 7, 1, 7, 2, 2, 7, 8, 2, 8, 3, 3, 8, 5, 3, 5, 0};  // sides
  compute_vertex_normals(m);
  return m;
}

TEST(ProxyInPit, TheApexHoldsTheProxy) {
  const Scene scene = scene_of("pit", make_pit());
  const Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{0.3, -0.2, 10.0};
  state.reset(glm::vec3(hip));
  const Contact c = move(state, bvh, hip, {0.3, -0.2, -8.0}, 200);
  ASSERT_TRUE(c.in_contact());
  EXPECT_LE(glm::length(state.position_mm - glm::dvec3(0.0, 0.0, -5.0)), 2.0 * eps);
  EXPECT_GT(state.position_mm.z, -5.0);
}

TEST(ProxyOnThinPlate, AFastMoveThroughItIsStoppedOnTop) {
  const Scene scene = scene_of("plate", make_box({100.0f, 100.0f, 0.1f}));  // top at z = 0.05
  const Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{1.0, 2.0, 10.0};
  state.reset(glm::vec3(hip));
  Contact c = move(state, bvh, hip, {1.0, 2.0, -10.0}, 1);  // 20 mm in one tick
  ASSERT_TRUE(c.in_contact());
  expect_near(state.position_mm, {1.0, 2.0, 0.05 + eps}, 1e-6, "proxy");
  EXPECT_GT(c.normal.z, 0.999f);
  // Below the plate the tip drags the proxy along the top.
  for (int i = 1; i <= 100; ++i) {
    c = move(state, bvh, hip, hip + glm::dvec3(0.2, -0.3, 0.0), 1);
    ASSERT_TRUE(c.in_contact());
    const glm::dvec3 h(c.hip_mm);
    expect_near(state.position_mm, {h.x, h.y, double(0.05f) + eps}, 1e-6, "proxy");
  }
  // Back up through it in one tick: released, at the tip.
  c = move(state, bvh, hip, hip + glm::dvec3(0.0, 0.0, 20.0), 1);
  EXPECT_FALSE(c.in_contact());
  expect_near(state.position_mm, glm::dvec3(c.hip_mm), 1e-12, "proxy");
}

// A sheet of 0.5 mm cells (z = 0, one-sided, its border at x = 10). Under it, the tip drags the proxy
// along the top; then it jumps 1 mm in one tick to 0.8 mm past the border, more than a triangle
// beyond the one the proxy rests on, so the proxy strides along the plane. There the plane holds
// nothing up: the proxy is released at the tip.
TEST(ProxyOnSheet, AStridePastItsBorderReleasesTheProxy) {
  const Scene scene = scene_of("sheet", make_grid(20.0f, 40));
  const Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{5.3, 0.2, 3.0};
  state.reset(glm::vec3(hip));
  Contact c = move(state, bvh, hip, {5.3, 0.2, -0.5}, 10);
  ASSERT_TRUE(c.in_contact());
  c = move(state, bvh, hip, {9.8, 0.2, -0.5}, 30);
  ASSERT_TRUE(c.in_contact());
  expect_near(state.position_mm, {9.8, 0.2, eps}, 1e-6, "proxy on the sheet");
  c = move(state, bvh, hip, {10.8, 0.2, -0.5}, 1);
  EXPECT_FALSE(c.in_contact());
  expect_near(state.position_mm, glm::dvec3(c.hip_mm), 1e-12, "proxy past the border");
}

TEST(ProxyAmongObjects, ReportsTheSceneIndexOfTheObjectTouched) {
  Scene scene;
  scene.objects.push_back({"ghost", make_box(glm::vec3(10.0f)), glm::mat4(1.0f), {}, {}});
  scene.objects.back().material.touchable = false;
  scene.objects.push_back(
      {"left", make_box(glm::vec3(10.0f)), glm::translate(glm::mat4(1.0f), {-20.0f, 0.0f, 0.0f}), {}, {}});
  scene.objects.push_back(
      {"right", make_box(glm::vec3(10.0f)), glm::translate(glm::mat4(1.0f), {20.0f, 0.0f, 0.0f}), {}, {}});
  const Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{-20.0, 1.0, 10.0};
  state.reset(glm::vec3(hip));
  Contact c = move(state, bvh, hip, {-20.0, 1.0, 4.0}, 20);
  ASSERT_TRUE(c.in_contact());
  EXPECT_EQ(c.object, 1);
  c = move(state, bvh, hip, {-20.0, 1.0, 10.0}, 20);
  EXPECT_FALSE(c.in_contact());
  c = move(state, bvh, hip, {0.0, 1.0, 3.0}, 20);  // through the ghost: nothing there
  EXPECT_FALSE(c.in_contact());
  c = move(state, bvh, hip, {20.0, 1.0, 10.0}, 20);
  c = move(state, bvh, hip, {20.0, 1.0, 3.0}, 20);
  ASSERT_TRUE(c.in_contact());
  EXPECT_EQ(c.object, 2);
  expect_near(state.position_mm, {20.0, 1.0, 5.0 + eps}, 1e-6, "proxy");
}

TEST(ProxyStartingInside, FeelsNothingUntilItHasLeftThenTheForceRampsFromZero) {
  const Scene scene = scene_of("sphere", make_sphere(30.0f, 2000));
  const Bvh bvh = Bvh::build(scene);
  const Material material{.stiffness_n_per_mm = 1.0f, .damping_ns_per_m = 0.0f};
  ProxyState state;  // never placed: the first step puts it at the HIP
  glm::dvec3 hip{0.0, 0.0, 0.0};
  std::vector<glm::dvec3> path = {{5.0, 5.0, 5.0}, {-20.0, 3.0, 1.0}, {0.0, 0.0, 25.0}, {0.0, 0.0, 40.0}};
  for (const glm::dvec3& to : path) {
    const glm::dvec3 from = hip;
    for (int i = 1; i <= 100; ++i) {
      hip = from + (to - from) * (i / 100.0);
      const Contact c = proxy_step(state, bvh, glm::vec3(hip));
      EXPECT_FALSE(c.in_contact());
      EXPECT_EQ(spring_damper(c, glm::vec3(0.0f), material, 10.0f).force_n, glm::vec3(0.0f));
    }
  }
  // Coming back in from outside: contact from zero depth, the force growing step by step.
  float previous = 0.0f;
  bool touched = false;
  for (int i = 1; i <= 100; ++i) {
    hip = glm::dvec3(0.0, 0.0, 40.0 - 0.15 * i);
    const Contact c = proxy_step(state, bvh, glm::vec3(hip));
    const float force = glm::length(spring_damper(c, glm::vec3(0.0f), material, 10.0f).force_n);
    if (c.in_contact()) {
      EXPECT_LE(force, previous + 0.15f * 1.0f + 1e-4f) << "step " << i;
      touched = true;
    }
    previous = force;
  }
  EXPECT_TRUE(touched);
  EXPECT_GT(previous, 4.0f);
}

TEST(ProxyWithBadInput, ANonFiniteHipLeavesTheProxyAndGivesNoContact) {
  const Scene scene = scene_of("cube", make_box(glm::vec3(40.0f)));
  const Bvh bvh = Bvh::build(scene);
  ProxyState state;
  glm::dvec3 hip{0.0, 0.0, 30.0};
  state.reset(glm::vec3(hip));
  move(state, bvh, hip, {0.0, 0.0, 18.0}, 20);
  const glm::dvec3 before = state.position_mm;
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const Contact c = proxy_step(state, bvh, glm::vec3(1.0f, bad, 2.0f));
    EXPECT_FALSE(c.in_contact());
    EXPECT_EQ(state.position_mm, before);
    EXPECT_TRUE(spring_damper(c, glm::vec3(0.0f), Material{}, 10.0f).invalid_input);
  }
  // And it carries on from where it was.
  EXPECT_TRUE(proxy_step(state, bvh, glm::vec3(0.0f, 0.0f, 18.0f)).in_contact());
}

TEST(ProxyOnEmptyScene, FollowsTheHip) {
  const Bvh bvh = Bvh::build(Scene{});
  ProxyState state;
  const Contact c = proxy_step(state, bvh, {1.0f, 2.0f, 3.0f});
  EXPECT_FALSE(c.in_contact());
  EXPECT_EQ(state.position_mm, glm::dvec3(1.0, 2.0, 3.0));
}

}  // namespace
}  // namespace palpate
