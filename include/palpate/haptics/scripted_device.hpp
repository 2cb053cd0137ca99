#pragma once
// A deterministic device for tests, benchmarks and demos: it follows a PressSlidePath or a
// SampledPath in device time and remembers the last force it was given. No hardware, no I/O in
// read() or write().
#include <variant>

#include "palpate/haptics/device.hpp"
#include "palpate/haptics/press_slide_path.hpp"
#include "palpate/haptics/sampled_path.hpp"

namespace palpate {

class ScriptedDevice final : public Device {
 public:
  using Path = std::variant<PressSlidePath, SampledPath>;

  // `repeat`: the path starts over after its duration (from its first sample time for a SampledPath).
  explicit ScriptedDevice(Path path, bool repeat = false, DeviceLimits limits = {});

  DeviceState read(double time_s) noexcept override;
  void write(glm::vec3 force_n) noexcept override;
  DeviceLimits limits() const noexcept override { return limits_; }

  // The last force written and how many writes there were. Not synchronised: read them on the
  // haptic thread or while the loop is stopped.
  glm::vec3 last_force() const noexcept { return last_force_; }
  unsigned long long writes() const noexcept { return writes_; }
  const Path& path() const noexcept { return path_; }

 private:
  Path path_;
  bool repeat_;
  DeviceLimits limits_;
  glm::vec3 last_force_{0.0f};
  unsigned long long writes_ = 0;
};

}  // namespace palpate
