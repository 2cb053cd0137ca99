#include "palpate/haptics/force.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <limits>

namespace palpate {
namespace {

// A tip 2 mm under a face with normal +z: SCP at z = 0, HIP at z = -2.
Contact pressed(float depth_mm = 2.0f, glm::vec3 normal = {0.0f, 0.0f, 1.0f}) {
  Contact c;
  c.object = 0;
  c.triangle = 5;
  c.normal = normal;
  c.point_mm = {1.0f, 2.0f, 0.0f};
  c.hip_mm = c.point_mm - depth_mm * normal;
  c.depth_mm = depth_mm;
  return c;
}

const Material material{.stiffness_n_per_mm = 0.5f, .damping_ns_per_m = 2.0f};

TEST(SpringDamper, SpringAloneIsStiffnessTimesDepthAlongTheNormal) {
  const ForceResult f = spring_damper(pressed(2.0f), glm::vec3(0.0f), material, 10.0f);
  EXPECT_EQ(f.force_n, glm::vec3(0.0f, 0.0f, 1.0f));  // 0.5 N/mm * 2 mm
  EXPECT_FALSE(f.clamped);
  EXPECT_FALSE(f.invalid_input);
}

TEST(SpringDamper, DampsOnlyTheNormalVelocityInNewtonSecondsPerMetre) {
  // Pressing in at 100 mm/s = 0.1 m/s: the damper adds 2 N s/m * 0.1 m/s = 0.2 N outward.
  ForceResult f = spring_damper(pressed(2.0f), {0.0f, 0.0f, -100.0f}, material, 10.0f);
  EXPECT_NEAR(f.force_n.z, 1.2f, 1e-6f);
  // Sliding sideways at 1 m/s adds nothing: no friction.
  f = spring_damper(pressed(2.0f), {1000.0f, -500.0f, 0.0f}, material, 10.0f);
  EXPECT_EQ(f.force_n, glm::vec3(0.0f, 0.0f, 1.0f));
  // Withdrawing at 100 mm/s takes 0.2 N off the spring.
  f = spring_damper(pressed(2.0f), {0.0f, 0.0f, 100.0f}, material, 10.0f);
  EXPECT_NEAR(f.force_n.z, 0.8f, 1e-6f);
}

TEST(SpringDamper, NeverPullsTheTipIntoTheSurface) {
  // Withdrawing at 1 m/s: the damper alone would pull with 2 N against a 1 N spring.
  const ForceResult f = spring_damper(pressed(2.0f), {0.0f, 0.0f, 1000.0f}, material, 10.0f);
  EXPECT_GE(glm::dot(f.force_n, glm::vec3(0.0f, 0.0f, 1.0f)), 0.0f);
  EXPECT_EQ(f.force_n, glm::vec3(0.0f));
}

TEST(SpringDamper, ClampsTheMagnitudeKeepingTheDirection) {
  const glm::vec3 n = glm::normalize(glm::vec3(1.0f, -2.0f, 2.0f));
  const ForceResult f = spring_damper(pressed(30.0f, n), glm::vec3(0.0f), material, 3.3f);
  EXPECT_TRUE(f.clamped);
  EXPECT_NEAR(glm::length(f.force_n), 3.3f, 1e-5f);
  EXPECT_NEAR(glm::dot(glm::normalize(f.force_n), n), 1.0f, 1e-6f);
}

TEST(SpringDamper, ClampsAForceJustOverTheLimit) {
  // 5 mm at 0.5 N/mm: 2.5 N against a 2 N device; 3 mm: 1.5 N, under it.
  const ForceResult f = spring_damper(pressed(5.0f), glm::vec3(0.0f), material, 2.0f);
  EXPECT_TRUE(f.clamped);
  EXPECT_NEAR(glm::length(f.force_n), 2.0f, 1e-5f);
  const ForceResult under = spring_damper(pressed(3.0f), glm::vec3(0.0f), material, 2.0f);
  EXPECT_FALSE(under.clamped);
  EXPECT_NEAR(glm::length(under.force_n), 1.5f, 1e-5f);
}

TEST(SpringDamper, NoContactNoForce) {
  const ForceResult f = spring_damper(Contact{}, {5.0f, 5.0f, 5.0f}, material, 10.0f);
  EXPECT_EQ(f.force_n, glm::vec3(0.0f));
  EXPECT_FALSE(f.invalid_input);
}

TEST(SpringDamper, NonFiniteInputGivesZeroForceAndAFlag) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::vector<std::pair<const char*, ForceResult>> cases;
  Contact c = pressed();
  c.hip_mm.x = nan;
  cases.push_back({"hip", spring_damper(c, glm::vec3(0.0f), material, 10.0f)});
  c = pressed();
  c.point_mm.z = inf;
  cases.push_back({"point", spring_damper(c, glm::vec3(0.0f), material, 10.0f)});
  c = pressed();
  c.normal.y = nan;
  cases.push_back({"normal", spring_damper(c, glm::vec3(0.0f), material, 10.0f)});
  cases.push_back({"velocity", spring_damper(pressed(), {0.0f, -inf, 0.0f}, material, 10.0f)});
  Material bad = material;
  bad.stiffness_n_per_mm = nan;
  cases.push_back({"stiffness", spring_damper(pressed(), glm::vec3(0.0f), bad, 10.0f)});
  bad = material;
  bad.damping_ns_per_m = inf;
  cases.push_back({"damping", spring_damper(pressed(), glm::vec3(0.0f), bad, 10.0f)});
  cases.push_back({"limit", spring_damper(pressed(), glm::vec3(0.0f), material, nan)});
  // Finite but so far apart that the spring overflows.
  c = pressed();
  c.hip_mm = {-3e38f, 0.0f, 0.0f};
  c.point_mm = {3e38f, 0.0f, 0.0f};
  cases.push_back({"overflow", spring_damper(c, glm::vec3(0.0f), material, 10.0f)});
  for (const auto& [what, f] : cases) {
    EXPECT_TRUE(f.invalid_input) << what;
    EXPECT_EQ(f.force_n, glm::vec3(0.0f)) << what;
  }
}

}  // namespace
}  // namespace palpate
