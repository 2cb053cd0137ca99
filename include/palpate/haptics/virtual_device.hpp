#pragma once
// A device for people without one: another thread (a GUI following the mouse) sets where the tip
// should be, and the haptic thread reads a tip that follows it smoothly (a first-order lag of
// `lag_s`), so that its velocity, and the damper's force, stay finite and smooth although the mouse
// moves in steps of a display frame. The forces written are kept for display.
//
// set_target() from one thread (the GUI), read() and write() from the haptic thread; target(),
// position() and last_force() from any thread. Nothing blocks or allocates.
#include <glm/vec3.hpp>

#include "palpate/haptics/device.hpp"
#include "palpate/haptics/latest.hpp"

namespace palpate {

class VirtualDevice final : public Device {
 public:
  explicit VirtualDevice(glm::vec3 start_mm = glm::vec3(0.0f), float lag_s = 0.02f, DeviceLimits limits = {});

  void set_target(glm::vec3 position_mm) noexcept { target_.store(position_mm); }
  glm::vec3 target() const noexcept { return target_.load(); }
  glm::vec3 position() const noexcept { return position_.load(); }
  glm::vec3 last_force() const noexcept { return force_.load(); }

  DeviceState read(double time_s) noexcept override;
  void write(glm::vec3 force_n) noexcept override { force_.store(force_n); }
  DeviceLimits limits() const noexcept override { return limits_; }

 private:
  Latest<glm::vec3> target_;
  Latest<glm::vec3> position_;
  Latest<glm::vec3> force_;
  float lag_s_;
  DeviceLimits limits_;
  glm::vec3 tip_;  // haptic thread only
  double last_time_s_ = -1.0;
};

}  // namespace palpate
