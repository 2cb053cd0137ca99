#include "palpate/haptics/scripted_device.hpp"

#include <cmath>

namespace palpate {

ScriptedDevice::ScriptedDevice(Path path, bool repeat, DeviceLimits limits)
    : path_(std::move(path)), repeat_(repeat), limits_(limits) {}

DeviceState ScriptedDevice::read(double time_s) noexcept {
  return std::visit(
      [&](const auto& path) {
        double t = time_s;
        if (repeat_) {
          const double start = path.start_s(), length = path.end_s() - start;
          if (length > 0.0 && t > start) t = start + std::fmod(t - start, length);
        }
        return path.sample(t);
      },
      path_);
}

void ScriptedDevice::write(glm::vec3 force_n) noexcept {
  last_force_ = force_n;
  ++writes_;
}

}  // namespace palpate
