#include "palpate/haptics/virtual_device.hpp"

#include <algorithm>
#include <cmath>

namespace palpate {

VirtualDevice::VirtualDevice(glm::vec3 start_mm, float lag_s, DeviceLimits limits)
    : target_(start_mm),
      position_(start_mm),
      force_(glm::vec3(0.0f)),
      lag_s_(std::max(lag_s, 1e-4f)),
      limits_(limits),
      tip_(start_mm) {}

DeviceState VirtualDevice::read(double time_s) noexcept {
  const glm::vec3 target = target_.load();
  DeviceState state;
  // A new run starts its clock at 0 again: restart the lag there rather than stepping backwards.
  const double dt = last_time_s_ < 0.0 || time_s < last_time_s_ ? 0.0 : time_s - last_time_s_;
  last_time_s_ = time_s;
  if (dt > 0.0) {
    // Exact step of dx/dt = (target - x) / lag over dt, stable for any dt.
    const float follow = 1.0f - float(std::exp(-dt / lag_s_));
    const glm::vec3 next = tip_ + (target - tip_) * follow;
    state.velocity_mm_per_s = (next - tip_) / float(dt);
    tip_ = next;
  }
  state.position_mm = tip_;
  position_.store(tip_);
  return state;
}

}  // namespace palpate
