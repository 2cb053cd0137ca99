#pragma once
// A 3-DOF haptic device as the haptic loop sees it. Real devices (OpenHaptics HD, Force Dimension,
// libnifalcon, a network stream) subclass Device in a module of their own; nothing else changes.
// read() and write() are called from the haptic thread once per tick: they must not allocate, lock,
// log or do I/O that can block.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace palpate {

struct DeviceState {
  glm::vec3 position_mm{0.0f};       // tool tip in the device's own frame, mm
  glm::vec3 velocity_mm_per_s{0.0f};  // in the device's frame
  std::uint32_t buttons = 0;          // bit i set while button i is down
};

struct DeviceLimits {
  float max_force_n = 3.3f;            // nominal continuous force (a PHANTOM Omni: 3.3 N)
  float max_stiffness_n_per_mm = 2.0f;  // highest stable spring constant
};

class Device {
 public:
  virtual ~Device() = default;
  // Samples the device at haptic time `time_s` (seconds since the loop started).
  virtual DeviceState read(double time_s) noexcept = 0;
  // Commands a force in newtons, in the device's frame.
  virtual void write(glm::vec3 force_n) noexcept = 0;
  virtual DeviceLimits limits() const noexcept { return {}; }
};

// A device that stays at the origin and ignores forces: runs the loop with no hardware.
class NullDevice final : public Device {
 public:
  DeviceState read(double time_s) noexcept override;
  void write(glm::vec3 force_n) noexcept override;
};

}  // namespace palpate
