#include "palpate/haptics/device.hpp"

namespace palpate {

DeviceState NullDevice::read(double) noexcept {
  return {};
}
void NullDevice::write(glm::vec3) noexcept {}

}  // namespace palpate
