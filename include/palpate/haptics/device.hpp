#pragma once
// A 3-DOF haptic device as the haptic loop sees it: a tool-tip position, velocity and buttons in the
// device's own frame and units (mm), a force in newtons out.
//
// Adding a real device (OpenHaptics HD, Force Dimension DHD, libnifalcon, a network stream) is a
// module of its own that touches nothing else: one header and one source file that subclass Device,
// built only when the vendor SDK is found. For example, src/devices/openhaptics_device.cpp with
//     class OpenHapticsDevice final : public Device {  // hdInitDevice in the constructor (may throw)
//       DeviceState read(double) noexcept override;   // hdBeginFrame; hdGetDoublev(HD_CURRENT_POSITION...)
//       void write(glm::vec3 f) noexcept override;     // hdSetDoublev(HD_CURRENT_FORCE...); hdEndFrame
//       DeviceLimits limits() const noexcept override;  // HD_NOMINAL_MAX_CONTINUOUS_FORCE,
//       HD_NOMINAL_MAX_STIFFNESS
//     };
// and in CMakeLists.txt a `palpate_openhaptics` library guarded by `find_library(HD ...)` that links
// palpate_haptics. The application hands the device to HapticLoop like any other; HapticLoop owns the
// clock, so a device whose SDK runs its own servo thread (hdScheduleAsynchronous) exchanges the latest
// state and force with it through palpate::Latest rather than driving the loop.
//
// read() and write() are called from the haptic thread once per tick, read first: they must not
// allocate, lock, log or do I/O that can block. Setup (opening, calibrating) happens in constructors,
// which may throw palpate::Error.
#include <cstdint>
#include <glm/vec3.hpp>

namespace palpate {

struct DeviceState {
  glm::vec3 position_mm{0.0f};        // tool tip in the device's own frame, mm
  glm::vec3 velocity_mm_per_s{0.0f};  // in the device's frame, mm/s
  std::uint32_t buttons = 0;          // bit i set while button i is down
};

struct DeviceLimits {
  float max_force_n = 3.3f;             // nominal continuous force, N (a PHANTOM Omni: 3.3 N)
  float max_stiffness_n_per_mm = 2.0f;  // highest stable spring constant at the device, N/mm
};

class Device {
 public:
  virtual ~Device() = default;
  // Samples the device at haptic time `time_s` (seconds since the loop started). A device reports a
  // fault by returning non-finite values; the loop then commands zero force and counts the tick.
  virtual DeviceState read(double time_s) noexcept = 0;
  // Commands a force in newtons, in the device's frame; held until the next write.
  virtual void write(glm::vec3 force_n) noexcept = 0;
  virtual DeviceLimits limits() const noexcept { return {}; }
};

// A device that stays at its origin and ignores forces: runs the loop with no hardware.
class NullDevice final : public Device {
 public:
  DeviceState read(double time_s) noexcept override;
  void write(glm::vec3 force_n) noexcept override;
};

}  // namespace palpate
