#include "palpate/haptics/virtual_device.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace palpate {
namespace {

TEST(VirtualDevice, FollowsTheTargetWithAFirstOrderLag) {
  VirtualDevice device({0, 0, 0}, 0.02f);
  device.read(0.0);
  device.set_target({10, 0, 0});
  // After t seconds a first-order lag has covered 1 - exp(-t / lag) of a step.
  for (int tick = 1; tick <= 20; ++tick) {
    const DeviceState state = device.read(tick * 1e-3);
    const float expected = 10.0f * (1.0f - std::exp(-float(tick) * 1e-3f / 0.02f));
    EXPECT_NEAR(state.position_mm.x, expected, 1e-4f) << "tick " << tick;
    // The velocity is that of the last step: finite, positive, bounded by the step over the lag.
    EXPECT_GT(state.velocity_mm_per_s.x, 0.0f);
    EXPECT_LE(state.velocity_mm_per_s.x, 10.0f / 0.02f + 1e-3f);
  }
  EXPECT_EQ(device.position(), device.read(20e-3).position_mm);
}

TEST(VirtualDevice, ARestartedClockDoesNotJumpAndForcesAreKept) {
  VirtualDevice device({1, 2, 3});
  device.read(5.0);
  device.set_target({1, 2, 13});
  const DeviceState restarted = device.read(0.0);
  EXPECT_EQ(restarted.position_mm, glm::vec3(1, 2, 3));
  EXPECT_EQ(restarted.velocity_mm_per_s, glm::vec3(0.0f));
  device.write({0.5f, 0, 0});
  EXPECT_EQ(device.last_force(), glm::vec3(0.5f, 0, 0));
  EXPECT_EQ(device.target(), glm::vec3(1, 2, 13));
}

}  // namespace
}  // namespace palpate
