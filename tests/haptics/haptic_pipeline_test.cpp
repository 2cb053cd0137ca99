// One haptic tick end to end: the device-to-scene transform, the touched object's material, the
// device's force limit, and non-finite device input (zero force, a flag, the loop goes on).
#include "palpate/haptics/haptic_pipeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/vector_relational.hpp>
#include <limits>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/haptic_loop.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate {
namespace {

// Two 20 mm cubes with their top faces at z = 10: a soft one at x = -30, a stiff one at x = +30.
Scene two_cubes() {
  Scene scene;
  Material soft, stiff;
  soft.stiffness_n_per_mm = 0.2f;
  stiff.stiffness_n_per_mm = 0.8f;
  scene.objects.push_back(
      {"soft", make_box(glm::vec3(20.0f)), glm::translate(glm::mat4(1.0f), {-30, 0, 0}), soft, {}});
  scene.objects.push_back(
      {"stiff", make_box(glm::vec3(20.0f)), glm::translate(glm::mat4(1.0f), {30, 0, 0}), stiff, {}});
  return scene;
}

// From 10 mm above `surface_point` down to `depth` below it in 0.1 s, then holding still.
SampledPath press(glm::vec3 surface_point, glm::vec3 normal, float depth) {
  return SampledPath({{0.0, surface_point + 10.0f * normal}, {0.1, surface_point - depth * normal}});
}

// Runs the pipeline for `ticks` simulated milliseconds and returns the last result.
TickResult run(HapticPipeline& pipeline, int ticks) {
  TickResult result;
  for (int k = 0; k < ticks; ++k) result = pipeline.tick(std::uint64_t(k), k * 1e-3);
  return result;
}

class NanDevice final : public Device {
 public:
  explicit NanDevice(SampledPath path) : inner_(std::move(path)) {}
  DeviceState read(double time_s) noexcept override {
    DeviceState state = inner_.read(time_s);
    if (time_s >= nan_from_s && time_s < nan_until_s)
      state.position_mm.y = std::numeric_limits<float>::quiet_NaN();
    if (time_s >= inf_velocity_at_s && time_s < inf_velocity_at_s + 0.0005) {
      state.velocity_mm_per_s.x = std::numeric_limits<float>::infinity();
    }
    return state;
  }
  void write(glm::vec3 force_n) noexcept override {
    inner_.write(force_n);
    forces.push_back(force_n);
  }
  double nan_from_s = 0.2, nan_until_s = 0.25, inf_velocity_at_s = 0.3;
  std::vector<glm::vec3> forces;

 private:
  ScriptedDevice inner_;
};

TEST(HapticPipelineTest, ForceUsesTheTouchedObjectsStiffness) {
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  DeviceLimits roomy;
  roomy.max_force_n = 100.0f;
  ScriptedDevice on_soft(press({-30, 0, 10}, {0, 0, 1}, 2.0f), false, roomy);
  ScriptedDevice on_stiff(press({30, 0, 10}, {0, 0, 1}, 2.0f), false, roomy);
  HapticPipeline soft_pipeline(on_soft, scene, bvh);
  HapticPipeline stiff_pipeline(on_stiff, scene, bvh);
  const TickResult soft = run(soft_pipeline, 300);
  const TickResult stiff = run(stiff_pipeline, 300);
  ASSERT_TRUE(soft.contact.in_contact());
  ASSERT_TRUE(stiff.contact.in_contact());
  EXPECT_EQ(soft.contact.object, 0);
  EXPECT_EQ(stiff.contact.object, 1);
  // At rest 2 mm deep in a flat face: F = k p along +z.
  EXPECT_NEAR(soft.force_n.z, 0.2f * 2.0f, 0.01f);
  EXPECT_NEAR(stiff.force_n.z, 0.8f * 2.0f, 0.04f);
  EXPECT_NEAR(glm::length(glm::vec2(stiff.force_n)), 0.0f, 1e-4f);
  EXPECT_EQ(on_stiff.last_force(), stiff.force_n) << "identity transform: the device gets the scene force";
  EXPECT_EQ(soft.contact.tick, 299u);
  EXPECT_DOUBLE_EQ(soft.contact.time_s, 0.299);
}

TEST(HapticPipelineTest, ForceIsClampedToTheDevicesMaximum) {
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  DeviceLimits weak;
  weak.max_force_n = 0.5f;
  ScriptedDevice device(press({30, 0, 10}, {0, 0, 1}, 4.0f), false, weak);
  HapticPipeline pipeline(device, scene, bvh);
  EXPECT_EQ(pipeline.limits().max_force_n, 0.5f);
  const TickResult result = run(pipeline, 300);
  ASSERT_TRUE(result.contact.in_contact());
  EXPECT_TRUE(result.clamped);
  EXPECT_NEAR(glm::length(result.force_n), 0.5f, 1e-5f);
  EXPECT_GT(result.force_n.z, 0.0f);
}

TEST(HapticPipelineTest, DeviceFrameIsScaledRotatedAndMovedIntoTheScene) {
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  // Device axes turned 90 degrees about z, 2 scene mm per device mm, device origin at the stiff
  // cube's top centre.
  DeviceTransform transform;
  transform.scale = 2.0f;
  transform.rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {0, 0, 1}));
  transform.translation_mm = {30, 0, 10};
  // 1.5 device mm below the device origin: 3 scene mm into the stiff cube.
  DeviceLimits roomy;
  roomy.max_force_n = 100.0f;
  ScriptedDevice device(press({0, 0, 0}, {0, 0, 1}, 1.5f), false, roomy);
  HapticPipeline pipeline(device, scene, bvh, transform);
  const TickResult result = run(pipeline, 300);
  ASSERT_TRUE(result.contact.in_contact());
  EXPECT_NEAR(result.contact.hip_mm.x, 30.0f, 1e-4f);
  EXPECT_NEAR(result.contact.hip_mm.z, 7.0f, 1e-4f);
  EXPECT_NEAR(result.contact.depth_mm, 3.0f, 0.01f);
  EXPECT_NEAR(result.force_n.z, 0.8f * 3.0f, 0.05f);
  // Off-centre: a device +x step is a scene +y step (rotation) of twice the length (scale).
  ScriptedDevice stepped(press({1, 0, 0}, {0, 0, 1}, 1.5f), false, roomy);
  HapticPipeline stepped_pipeline(stepped, scene, bvh, transform);
  const TickResult moved = run(stepped_pipeline, 300);
  EXPECT_NEAR(moved.contact.hip_mm.x, 30.0f, 1e-4f);
  EXPECT_NEAR(moved.contact.hip_mm.y, 2.0f, 1e-4f);
  // A force along scene +y would reach the device along device -x; along z it stays along z.
  EXPECT_NEAR(transform.force_to_device({0, 1, 0}).x, 1.0f, 1e-6f);
  EXPECT_NEAR(stepped.last_force().z, moved.force_n.z, 1e-6f);
}

TEST(HapticPipelineTest, NonFiniteDeviceInputGivesZeroForceAndAFlagWhileTheLoopGoesOn) {
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  DeviceLimits roomy;
  roomy.max_force_n = 100.0f;
  NanDevice device(press({30, 0, 10}, {0, 0, 1}, 2.0f));
  HapticPipeline pipeline(device, scene, bvh);
  int invalid = 0;
  for (int k = 0; k < 400; ++k) {
    const double time = k * 1e-3;
    const TickResult result = pipeline.tick(std::uint64_t(k), time);
    const bool bad = (time >= 0.2 && time < 0.25) || (time >= 0.3 && time < 0.3005);
    ASSERT_EQ(result.invalid_input, bad) << "tick " << k;
    ASSERT_TRUE(std::isfinite(result.force_n.x) && std::isfinite(result.force_n.y) &&
                std::isfinite(result.force_n.z));
    if (bad) {
      ++invalid;
      EXPECT_EQ(result.force_n, glm::vec3(0.0f)) << "tick " << k;
      EXPECT_EQ(device.forces.back(), glm::vec3(0.0f)) << "zero force written at tick " << k;
      EXPECT_FALSE(result.contact.in_contact());
      EXPECT_EQ(result.contact.tick, std::uint64_t(k));
    } else if (time > 0.15) {
      // Pressed 2 mm before, between and after the bad ticks: the proxy kept its place.
      EXPECT_TRUE(result.contact.in_contact()) << "tick " << k;
      EXPECT_NEAR(result.force_n.z, 0.8f * 2.0f, 0.05f) << "tick " << k;
    }
  }
  EXPECT_EQ(invalid, 51);
  EXPECT_EQ(device.forces.size(), 400u) << "a force is written every tick";
}

// Time advances only by sleeping: each run_ticks() tick is exactly one period.
class StepClock final : public LoopClock {
 public:
  std::int64_t now_ns() noexcept override { return now_; }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override { now_ = std::max(now_, deadline_ns); }

 private:
  std::int64_t now_ = 0;
};

TEST(HapticPipelineTest, TheLoopCountsEveryInvalidInputTick) {
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  NanDevice device(press({30, 0, 10}, {0, 0, 1}, 2.0f));
  // On the step clock tick k reads the device at k ms (the first tick of a run at one period, 1 ms):
  // device times 1..10 ms are non-finite, ticks 0..9.
  device.nan_from_s = 0.0005;
  device.nan_until_s = 0.0105;
  device.inf_velocity_at_s = 10.0;
  HapticLoopParams params;
  params.realtime_priority = false;
  StepClock clock;
  HapticLoop loop(device, scene, bvh, params, &clock);
  loop.run_ticks(30);
  const LoopStatistics stats = loop.statistics();
  EXPECT_EQ(stats.ticks, 30u);
  EXPECT_EQ(stats.invalid_input_ticks, 10u);
  EXPECT_EQ(loop.latest().contact.tick, 29u);
  EXPECT_FALSE(loop.latest().invalid_input);
}

// The device frame rotated about x (device +y is scene +z), scaled 2x: both the force sent back and the
// velocity the damper sees go through the rotation, the velocity through the scale too.
TEST(HapticPipelineTest, ForceAndVelocityGoThroughTheDeviceFrame) {
  Scene scene = two_cubes();
  scene.objects[1].material.damping_ns_per_m = 50.0f;
  const Bvh bvh = Bvh::build(scene);
  DeviceTransform transform;
  transform.scale = 2.0f;
  transform.rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1, 0, 0}));
  transform.translation_mm = {30, 0, 10};  // the stiff cube's top centre
  // Down the device's y axis at 20 mm/s: scene z falls at 40 mm/s; through the top face at device time 0.5 s.
  DeviceLimits roomy;
  roomy.max_force_n = 100.0f;
  ScriptedDevice device(SampledPath({{0.0, {0, 10, 0}}, {1.0, {0, -10, 0}}}), false, roomy);
  HapticPipeline pipeline(device, scene, bvh, transform);
  TickResult result;
  for (int k = 0; k <= 700; ++k) result = pipeline.tick(std::uint64_t(k), k * 1e-3);
  ASSERT_TRUE(result.contact.in_contact());
  const double depth = 2.0 * (0.7 - 0.5) * 20.0 + ProxyParams{}.surface_epsilon_mm;  // scene mm
  // Spring k p plus the damper b v_n: 50 N s/m x 0.040 m/s = 2 N, both along scene +z.
  EXPECT_NEAR(result.force_n.z, 0.8 * depth + 2.0, 1e-3);
  EXPECT_NEAR(glm::length(glm::vec2(result.force_n)), 0.0f, 1e-4f);
  // Sent to the device along its own +y (the rotation's inverse), with the magnitude unchanged.
  EXPECT_NEAR(device.last_force().y, result.force_n.z, 1e-4f);
  EXPECT_NEAR(device.last_force().x, 0.0f, 1e-4f);
  EXPECT_NEAR(device.last_force().z, 0.0f, 1e-4f);
}

// Between ticks the pipeline readies the proxy for the next one: sliding over the stiff cube's top,
// after each prepare_next_tick() the proxy lies within a quarter of its neighbourhood's half-width of
// the box's centre (regathered around it once it strays further).
TEST(HapticPipelineTest, BetweenTicksTheNeighbourhoodIsRegatheredAroundTheProxy) {
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  ScriptedDevice device(
      SampledPath({{0.0, {22.0f, -8.0f, 12.0f}}, {0.05, {22.0f, -8.0f, 9.0f}}, {0.5, {38.0f, 8.0f, 9.0f}}}),
      false);
  HapticPipeline pipeline(device, scene, bvh);
  int contact_ticks = 0, regathered = 0;
  for (int k = 0; k < 500; ++k) {
    const TickResult result = pipeline.tick(std::uint64_t(k), k * 1e-3);
    const Bvh::Neighbourhood& near = pipeline.proxy_state().neighbourhood;
    const glm::vec3 box_before = near.low;
    pipeline.prepare_next_tick();
    if (!result.contact.in_contact()) continue;
    ++contact_ticks;
    regathered += near.low != box_before;
    const glm::dvec3 half = 0.5 * (glm::dvec3(near.high) - glm::dvec3(near.low));
    const glm::dvec3 off =
        glm::abs(pipeline.proxy_state().position_mm - 0.5 * (glm::dvec3(near.high) + glm::dvec3(near.low)));
    EXPECT_TRUE(glm::all(glm::lessThanEqual(off, 0.25 * half))) << "tick " << k;
  }
  EXPECT_GT(contact_ticks, 400);
  EXPECT_GT(regathered, 0);
}

TEST(DeviceTransformTest, MapsPointsVelocitiesAndForces) {
  DeviceTransform transform;
  transform.scale = 3.0f;
  transform.rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1, 0, 0}));  // y -> z
  transform.translation_mm = {1, 2, 3};
  const glm::vec3 scene = transform.point_to_scene({0, 1, 0});
  EXPECT_NEAR(scene.x, 1.0f, 1e-5f);
  EXPECT_NEAR(scene.y, 2.0f, 1e-5f);
  EXPECT_NEAR(scene.z, 6.0f, 1e-5f);
  const glm::vec3 back = transform.point_to_device(scene);
  EXPECT_NEAR(back.y, 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(back), 1.0f, 1e-5f);
  EXPECT_NEAR(transform.velocity_to_scene({0, 2, 0}).z, 6.0f, 1e-5f);
  EXPECT_NEAR(transform.force_to_device({0, 0, 1}).y, 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(transform.force_to_device({0, 0, 1})), 1.0f, 1e-6f) << "forces are not scaled";
}

TEST(DeviceTransformTest, FitWorkspaceCentresAndScalesUniformly) {
  const DeviceTransform fit = fit_workspace({{-80, -60, -40}, {80, 60, 40}}, {{0, 0, 0}, {320, 200, 160}});
  EXPECT_FLOAT_EQ(fit.scale, 200.0f / 120.0f);  // y is the tightest axis
  const glm::vec3 centre = fit.point_to_scene({0, 0, 0});
  EXPECT_FLOAT_EQ(centre.x, 160.0f);
  EXPECT_FLOAT_EQ(centre.y, 100.0f);
  EXPECT_FLOAT_EQ(centre.z, 80.0f);
  EXPECT_NEAR(fit.point_to_scene({0, 60, 0}).y, 200.0f, 1e-4f);
}

TEST(DeviceTransformTest, RejectsBadScaleAndNonRotations) {
  DeviceTransform zero;
  zero.scale = 0.0f;
  EXPECT_THROW(validate_device_transform(zero), Error);
  DeviceTransform sheared;
  sheared.rotation[1][0] = 0.3f;
  EXPECT_THROW(validate_device_transform(sheared), Error);
  DeviceTransform mirrored;
  mirrored.rotation[2][2] = -1.0f;
  EXPECT_THROW(validate_device_transform(mirrored), Error);
  const Scene scene = two_cubes();
  const Bvh bvh = Bvh::build(scene);
  NullDevice device;
  EXPECT_THROW(HapticPipeline(device, scene, bvh, mirrored), Error);
  HapticLoopParams too_fast;
  too_fast.rate_hz = 1e6;
  EXPECT_THROW(HapticLoop(device, scene, bvh, too_fast), Error);
  EXPECT_NO_THROW(validate_device_transform(DeviceTransform{}));
}

}  // namespace
}  // namespace palpate
