// PressSlidePath against its analytic definition: approach along the normal, press, slide on the
// plane or sphere with the depth p + a sin(2 pi s / L), pull out; velocities against finite
// differences of the positions.
#include "palpate/haptics/press_slide_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate {
namespace {

constexpr float pi = std::numbers::pi_v<float>;

void expect_near(glm::vec3 got, glm::vec3 want, float tolerance, const char* what) {
  EXPECT_NEAR(got.x, want.x, tolerance) << what;
  EXPECT_NEAR(got.y, want.y, tolerance) << what;
  EXPECT_NEAR(got.z, want.z, tolerance) << what;
}

PressSlideParams flat_spec() {
  PressSlideParams spec;
  spec.surface_point_mm = {1.0f, 2.0f, 3.0f};
  spec.normal = {0.0f, 0.0f, 2.0f};           // normalised on use
  spec.slide_direction = {1.0f, 0.0f, 0.5f};  // projected onto the plane: +x
  return spec;
}

TEST(PressSlidePathTest, PhasesLastWhatTheSpeedsSay) {
  const PressSlidePath path(flat_spec());
  // 20 mm above to 2.5 mm below at 25 mm/s; 52 mm at 25 mm/s; back from depth 2.5 (a whole depth
  // cycle ends where it began) to 20 mm above at 25 mm/s.
  EXPECT_DOUBLE_EQ(path.approach_end_s(), 22.5 / 25.0);
  EXPECT_NEAR(path.slide_end_s(), 0.9 + 52.0 / 25.0, 1e-9);
  EXPECT_NEAR(path.retract_end_s(), path.slide_end_s() + 22.5 / 25.0, 1e-5);
  EXPECT_DOUBLE_EQ(path.duration_s(), path.retract_end_s());
}

TEST(PressSlidePathTest, FlatPathFollowsItsAnalyticPositions) {
  const PressSlideParams spec = flat_spec();
  const PressSlidePath path(spec);
  const glm::vec3 p = spec.surface_point_mm, n{0, 0, 1}, t{1, 0, 0};
  expect_near(path.sample(0.0).position_mm, p + 20.0f * n, 1e-5f, "start 20 mm above");
  expect_near(path.sample(0.4).position_mm, p + (20.0f - 25.0f * 0.4f) * n, 1e-5f, "approach at 25 mm/s");
  expect_near(path.sample(0.4).velocity_mm_per_s, -25.0f * n, 1e-5f, "approach velocity");
  expect_near(path.sample(path.approach_end_s()).position_mm, p - 2.5f * n, 1e-4f, "pressed to 2.5 mm");
  for (const float s : {0.0f, 6.5f, 13.0f, 26.0f, 39.0f, 51.0f}) {
    const double time = path.approach_end_s() + s / 25.0;
    const float depth = 2.5f + 1.5f * std::sin(2.0f * pi * s / 52.0f);
    expect_near(path.sample(time).position_mm, p + s * t - depth * n, 1e-4f, "slide");
  }
  // The depth spans 1..4 mm: deepest a quarter of the way, shallowest three quarters.
  EXPECT_NEAR(path.depth_at(13.0f), 4.0f, 1e-5f);
  EXPECT_NEAR(path.depth_at(39.0f), 1.0f, 1e-5f);
  const glm::vec3 end_point = p + 52.0f * t;
  expect_near(path.sample(path.slide_end_s() + 0.2).position_mm, end_point + (-2.5f + 25.0f * 0.2f) * n,
              1e-3f, "pull out at 25 mm/s");
  expect_near(path.sample(path.duration_s() + 5.0).position_mm, end_point + 20.0f * n, 1e-3f,
              "rests 20 mm above");
  expect_near(path.sample(path.duration_s() + 5.0).velocity_mm_per_s, glm::vec3(0.0f), 0.0f, "at rest");
  expect_near(path.sample(-1.0).position_mm, p + 20.0f * n, 1e-5f, "clamped before the start");
}

TEST(PressSlidePathTest, SphericalSlideKeepsItsDepthBelowTheSphere) {
  PressSlideParams spec;
  spec.surface_point_mm = {0.0f, 0.0f, 50.0f};  // the top of a sphere of radius 50 about the origin
  spec.normal = {0.0f, 0.0f, 1.0f};
  spec.slide_direction = {0.0f, 1.0f, 0.0f};
  spec.curvature_radius_mm = 50.0f;
  const PressSlidePath path(spec);
  for (const float s : {0.0f, 10.0f, 26.0f, 45.0f, 52.0f}) {
    const double time = path.approach_end_s() + s / 25.0;
    const glm::vec3 tip = path.sample(std::min(time, path.slide_end_s() - 1e-9)).position_mm;
    const float depth = 2.5f + 1.5f * std::sin(2.0f * pi * s / 52.0f);
    EXPECT_NEAR(glm::length(tip), 50.0f - depth, 1e-3f) << "s = " << s;
    // Arc length s on the surface is an angle s / R from the start, in the y-z plane.
    EXPECT_NEAR(std::atan2(tip.y, tip.z), s / 50.0f, 1e-4f) << "s = " << s;
    EXPECT_NEAR(tip.x, 0.0f, 1e-5f);
  }
  // The pull-out leaves along the sphere's normal at the end of the slide.
  const glm::vec3 out = path.sample(path.duration_s()).position_mm;
  EXPECT_NEAR(glm::length(out), 70.0f, 1e-3f);
  EXPECT_NEAR(std::atan2(out.y, out.z), 52.0f / 50.0f, 1e-4f);
}

TEST(PressSlidePathTest, VelocityIsTheDerivativeOfThePosition) {
  for (const float radius : {0.0f, 50.0f}) {
    PressSlideParams spec = flat_spec();
    spec.curvature_radius_mm = radius;
    spec.depth_cycles = 2.0f;
    const PressSlidePath path(spec);
    const double h = 1e-4;
    for (double time = 0.05; time < path.duration_s(); time += 0.173) {
      // Skip samples whose difference would straddle a phase boundary.
      const bool near_boundary = std::abs(time - path.approach_end_s()) < 2 * h ||
                                 std::abs(time - path.slide_end_s()) < 2 * h ||
                                 std::abs(time - path.retract_end_s()) < 2 * h;
      if (near_boundary) continue;
      const glm::vec3 numeric =
          (path.sample(time + h).position_mm - path.sample(time - h).position_mm) / float(2 * h);
      expect_near(path.sample(time).velocity_mm_per_s, numeric, 0.05f, "velocity");
    }
  }
}

TEST(PressSlidePathTest, RejectsBadSpecsNamingTheField) {
  const auto message = [](PressSlideParams spec) {
    try {
      PressSlidePath{spec};
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  PressSlideParams along_normal = flat_spec();
  along_normal.slide_direction = {0.0f, 0.0f, -1.0f};
  EXPECT_NE(message(along_normal).find("slide_direction"), std::string::npos);
  PressSlideParams zero_normal = flat_spec();
  zero_normal.normal = glm::vec3(0.0f);
  EXPECT_NE(message(zero_normal).find("normal"), std::string::npos);
  PressSlideParams stopped = flat_spec();
  stopped.slide_speed_mm_per_s = 0.0f;
  EXPECT_NE(message(stopped).find("slide_speed_mm_per_s"), std::string::npos);
  PressSlideParams tight = flat_spec();
  tight.curvature_radius_mm = 3.0f;
  EXPECT_NE(message(tight).find("curvature_radius_mm"), std::string::npos);
  PressSlideParams nan_point = flat_spec();
  nan_point.surface_point_mm.x = std::nanf("");
  EXPECT_NE(message(nan_point).find("surface_point_mm"), std::string::npos);
  PressSlideParams low_start = flat_spec();
  low_start.start_height_mm = -3.0f;
  EXPECT_NE(message(low_start).find("start_height_mm"), std::string::npos);
}

TEST(PressSlidePathTest, AimsAtAVertexOfAnObjectInWorldCoordinates) {
  SceneObject ball;
  ball.name = "ball";
  ball.mesh = make_sphere(30.0f, 2000);
  ball.transform = glm::translate(glm::mat4(1.0f), {100.0f, 0.0f, 0.0f});
  const std::size_t vertex = 700;
  const glm::vec3 local = ball.mesh.positions_mm[vertex];
  const PressSlideParams aimed = aim_press_slide(ball, vertex, {0.0f, 0.0f, 1.0f});
  expect_near(aimed.surface_point_mm, local + glm::vec3(100.0f, 0.0f, 0.0f), 1e-4f, "the vertex, in world");
  // On a sphere the smoothed normal is the radial direction and the curvature its radius.
  expect_near(glm::normalize(aimed.normal), glm::normalize(local), 0.01f, "radial normal");
  EXPECT_NEAR(aimed.curvature_radius_mm, 30.0f, 0.05f);
  EXPECT_EQ(aimed.press_depth_mm, PressSlideParams{}.press_depth_mm) << "other fields kept";
  // The aimed path presses 2.5 mm into the ball along the radius.
  const PressSlidePath path(aimed);
  EXPECT_NEAR(glm::length(path.sample(path.approach_end_s()).position_mm - glm::vec3(100.0f, 0.0f, 0.0f)),
              27.5f, 0.05f);
  EXPECT_THROW(aim_press_slide(ball, 5000, {0.0f, 0.0f, 1.0f}), Error);
}

TEST(ScriptedDeviceTest, FollowsItsPathRepeatsAndKeepsTheLastForce) {
  const PressSlidePath path(flat_spec());
  ScriptedDevice once(path);
  ScriptedDevice repeating(path, true);
  const double t = 0.7;
  expect_near(once.read(t).position_mm, path.sample(t).position_mm, 0.0f, "follows the path");
  expect_near(repeating.read(path.duration_s() + t).position_mm, path.sample(t).position_mm, 1e-3f,
              "starts over");
  expect_near(once.read(path.duration_s() + t).position_mm, path.sample(path.duration_s()).position_mm, 0.0f,
              "holds the end");
  EXPECT_EQ(once.writes(), 0u);
  once.write({1.0f, 2.0f, 3.0f});
  once.write({0.0f, 0.5f, 0.0f});
  EXPECT_EQ(once.writes(), 2u);
  expect_near(once.last_force(), {0.0f, 0.5f, 0.0f}, 0.0f, "last force");
  DeviceLimits limits;
  limits.max_force_n = 7.5f;
  EXPECT_EQ(ScriptedDevice(path, false, limits).limits().max_force_n, 7.5f);
}

TEST(NullDeviceTest, StaysAtTheOrigin) {
  NullDevice device;
  device.write({1.0f, 1.0f, 1.0f});
  const DeviceState state = device.read(3.0);
  expect_near(state.position_mm, glm::vec3(0.0f), 0.0f, "origin");
  expect_near(state.velocity_mm_per_s, glm::vec3(0.0f), 0.0f, "still");
  EXPECT_EQ(state.buttons, 0u);
}

}  // namespace
}  // namespace palpate
